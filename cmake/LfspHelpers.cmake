# lfsp_add_library(<stage> SOURCES ... DEPENDS ...)
#   Creates the library target lfsp_<stage> from <stage>/src, with the public headers in <stage>/include.
function(lfsp_add_library stage)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS;PRIVATE_DEPENDS" ${ARGN})
  set(target lfsp_${stage})
  add_library(${target} STATIC ${ARG_SOURCES})
  add_library(lfsp::${stage} ALIAS ${target})
  target_include_directories(${target} PUBLIC "${CMAKE_CURRENT_SOURCE_DIR}/include"
                                       PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}/src")
  target_link_libraries(${target} PUBLIC ${ARG_DEPENDS} PRIVATE ${ARG_PRIVATE_DEPENDS})
  lfsp_set_warnings(${target})
endfunction()

# lfsp_add_test(<stage> <name> SOURCES ... [DEPENDS ...] [LABELS ...])
#   One GoogleTest executable, registered in CTest as <stage>/<name> so `ctest -R <stage>/` runs one stage.
function(lfsp_add_test stage name)
  cmake_parse_arguments(ARG "" "TIMEOUT" "SOURCES;DEPENDS" ${ARGN})
  set(target test_${stage}_${name})
  add_executable(${target} ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE ${ARG_DEPENDS} lfsp_test_support GTest::gtest GTest::gtest_main)
  lfsp_set_warnings(${target})
  add_test(NAME ${stage}/${name} COMMAND ${target})
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  set_tests_properties(${stage}/${name} PROPERTIES TIMEOUT ${ARG_TIMEOUT}
    ENVIRONMENT "LFSP_SHARED_DATA=${PROJECT_SOURCE_DIR}/../shared/data;LFSP_SOURCE_DIR=${PROJECT_SOURCE_DIR};LFSP_BINARY=$<TARGET_FILE:lfsp>")
endfunction()

function(lfsp_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                           -Wold-style-cast -Wcast-align -Wunused
                                           # GCC 12 reports false positives inside libstdc++ string code
                                           # (GCC bug 105329); they say nothing about ours.
                                           -Wno-restrict -Wno-stringop-overflow)
  if(LFSP_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
