# lfsp's version, from one place: `git describe` of the newest tag v<X.Y.Z> reachable from HEAD, else the VERSION
# file (a clone without tags, a source archive). On a tag: X.Y.Z; N commits after it: X.Y.Z+N.g<hash>, which is both
# a PEP 440 and a Debian version, so the command, the Python module, every summary JSON, the wheel and the .deb all
# carry the same string.
#
# Sets LFSP_VERSION (the full string) and LFSP_VERSION_NUMBER (X.Y.Z, for project()). Configuration re-runs when HEAD
# moves or tags change, so a build never reports a stale version.

file(STRINGS "${CMAKE_CURRENT_LIST_DIR}/../VERSION" LFSP_VERSION LIMIT_COUNT 1)
string(STRIP "${LFSP_VERSION}" LFSP_VERSION)
if(NOT LFSP_VERSION MATCHES "^[0-9]+\\.[0-9]+\\.[0-9]+$")
  message(FATAL_ERROR "VERSION: expected X.Y.Z, found '${LFSP_VERSION}'")
endif()

find_package(Git QUIET)
if(GIT_FOUND)
  get_filename_component(_lfsp_source "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
  execute_process(COMMAND "${GIT_EXECUTABLE}" describe --tags --match "v[0-9]*" --long
                  WORKING_DIRECTORY "${_lfsp_source}" OUTPUT_VARIABLE _lfsp_describe ERROR_QUIET
                  RESULT_VARIABLE _lfsp_describe_failed OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT _lfsp_describe_failed AND _lfsp_describe MATCHES "^v([0-9]+\\.[0-9]+\\.[0-9]+)-([0-9]+)-(g[0-9a-f]+)$")
    set(LFSP_VERSION "${CMAKE_MATCH_1}")
    if(NOT CMAKE_MATCH_2 STREQUAL "0")
      string(APPEND LFSP_VERSION "+${CMAKE_MATCH_2}.${CMAKE_MATCH_3}")
    endif()
  endif()
  # Re-configure when HEAD moves (a commit, a checkout) or a tag is made.
  execute_process(COMMAND "${GIT_EXECUTABLE}" rev-parse --absolute-git-dir --git-common-dir --symbolic-full-name HEAD
                  WORKING_DIRECTORY "${_lfsp_source}" OUTPUT_VARIABLE _lfsp_git ERROR_QUIET
                  RESULT_VARIABLE _lfsp_git_failed OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT _lfsp_git_failed)
    string(REPLACE "\n" ";" _lfsp_git "${_lfsp_git}")
    list(GET _lfsp_git 0 _lfsp_git_dir)
    list(GET _lfsp_git 1 _lfsp_common_dir)
    get_filename_component(_lfsp_common_dir "${_lfsp_common_dir}" ABSOLUTE BASE_DIR "${_lfsp_source}")
    set(_lfsp_watched "${_lfsp_git_dir}/HEAD" "${_lfsp_common_dir}/packed-refs" "${_lfsp_common_dir}/refs/tags")
    list(LENGTH _lfsp_git _lfsp_git_lines)
    if(_lfsp_git_lines GREATER 2)
      list(GET _lfsp_git 2 _lfsp_head_ref)
      list(APPEND _lfsp_watched "${_lfsp_common_dir}/${_lfsp_head_ref}")
    endif()
    foreach(_lfsp_path ${_lfsp_watched})
      if(EXISTS "${_lfsp_path}")
        set_property(DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${_lfsp_path}")
      endif()
    endforeach()
  endif()
endif()
string(REGEX MATCH "^[0-9]+\\.[0-9]+\\.[0-9]+" LFSP_VERSION_NUMBER "${LFSP_VERSION}")
set_property(DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
                                                                   "${CMAKE_CURRENT_LIST_DIR}/../VERSION")
