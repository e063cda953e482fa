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
  target_link_libraries(${target} PRIVATE ${ARG_DEPENDS} lfsp_test_support lfsp::omp_wait_policy GTest::gtest
                                          GTest::gtest_main)
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

# lfsp_add_fuzz_target(<stage> <name> SOURCES ... [DEPENDS ...] [INCLUDES ...] [SEEDS dir...] [REPLAY arg...]
#                      [DICT file] [TIMEOUT s])
#   A fuzz target of one parser (its LLVMFuzzerTestOneInput in SOURCES), registered in CTest as <stage>/fuzz_<name>.
#   With -DLFSP_FUZZ=ON under clang (`make fuzz`): the libFuzzer binary fuzz_<name>, the whole tree instrumented (top
#   CMakeLists), its CTest test replaying the SEEDS folders, and a line in fuzz_targets.txt for tools/fuzz. Otherwise:
#   fuzz_replay_<name> (tests/decode/fuzz/replay_main.cc, with lfsp::omp_wait_policy like the tests) run with
#   REPLAY, the committed seeds and deterministic mutations of real files. DICT is a libFuzzer dictionary (tokens the
#   mutations insert: deep JSON nesting, extreme floats) that tools/fuzz passes as -dict=.
function(lfsp_add_fuzz_target stage name)
  cmake_parse_arguments(ARG "" "TIMEOUT;DICT" "SOURCES;DEPENDS;INCLUDES;SEEDS;REPLAY" ${ARGN})
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 120)
  endif()
  if(LFSP_FUZZ_BUILD)
    set(target fuzz_${name})
    add_executable(${target} ${ARG_SOURCES})
    target_link_options(${target} PRIVATE -fsanitize=fuzzer)
    set(existing_seeds "")
    foreach(seed ${ARG_SEEDS})
      if(EXISTS "${seed}")
        list(APPEND existing_seeds "${seed}")
      endif()
    endforeach()
    add_test(NAME ${stage}/fuzz_${name} COMMAND ${target} -runs=0 ${existing_seeds})
    string(REPLACE ";" " " seed_list "${existing_seeds}")
    file(APPEND "${CMAKE_BINARY_DIR}/fuzz_targets.txt"
         "${stage}/${name}|${CMAKE_CURRENT_BINARY_DIR}/${target}|${seed_list}|${ARG_DICT}\n")
    add_dependencies(lfsp_fuzz_targets ${target})
  else()
    set(target fuzz_replay_${name})
    add_executable(${target} ${ARG_SOURCES} "${PROJECT_SOURCE_DIR}/tests/decode/fuzz/replay_main.cc")
    lfsp_set_warnings(${target})
    # Passive OpenMP waits, as in the tests: spinning threads starved the replays beside a build (10x slower).
    target_link_libraries(${target} PRIVATE lfsp::omp_wait_policy)
    add_test(NAME ${stage}/fuzz_${name} COMMAND ${target} ${ARG_REPLAY})
  endif()
  target_include_directories(${target} PRIVATE "${PROJECT_SOURCE_DIR}/tests/decode/fuzz" ${ARG_INCLUDES})
  target_link_libraries(${target} PRIVATE ${ARG_DEPENDS})
  set_tests_properties(${stage}/fuzz_${name} PROPERTIES TIMEOUT ${ARG_TIMEOUT})
endfunction()
