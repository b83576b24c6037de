# physics_gtest_suites(TARGET [LABELS label...] [TIMEOUT seconds] [DISCOVERY_TIMEOUT seconds]
#                      [SUITE_LABELS label... SUITES suite...])
#
# One ctest test per GoogleTest suite of TARGET, named "Suite.*" and run as
# `TARGET --gtest_filter=Suite.*`, instead of gtest_discover_tests' one process per
# test case. Starting a test process is what costs for the small cases (the core's
# 322 unit cases took 15 s of CPU as 322 ctest processes, 4.3 s as its 52 suites);
# a suite per process keeps ctest's parallelism across suites, and `ctest -R '^Suite\.'`
# selects the same tests as before.
#
# The suites are listed after each build (`--gtest_list_tests`), as gtest_discover_tests
# does. TIMEOUT is per test case: a suite gets it times its number of cases, so no
# case has less time than before. LABELS go on every suite, SUITE_LABELS on the named
# SUITES only (the sanitizers' `tsan` and `asan` mark what scripts/test-tsan.sh and
# scripts/test-asan.sh run). The targets that carry a label are listed in the global
# property PHYSICS_LABELLED_<label> (tests/CMakeLists.txt builds one target of each).
set(PHYSICS_GTEST_SUITES_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/physics_gtest_suites_list.cmake")

function(physics_gtest_suites target)
  cmake_parse_arguments(arg "" "TIMEOUT;DISCOVERY_TIMEOUT" "LABELS;SUITE_LABELS;SUITES" ${ARGN})
  foreach(label IN LISTS arg_LABELS arg_SUITE_LABELS)
    set_property(GLOBAL APPEND PROPERTY PHYSICS_LABELLED_${label} ${target})
  endforeach()
  # Passed to the listing script as "Suite=label,label" words.
  string(REPLACE ";" "," suite_labels "${arg_SUITE_LABELS}")
  set(labelled_suites "")
  foreach(suite IN LISTS arg_SUITES)
    list(APPEND labelled_suites "${suite}=${suite_labels}")
  endforeach()
  # The tests' own code at -O1 in an optimised build: the code under test is in the
  # libraries, which keep the build type's -O3; the tests' setup and assertions
  # compile about 30% faster so (a clean build's time is mostly test files).
  if(CMAKE_BUILD_TYPE MATCHES "^(Release|RelWithDebInfo)$")
    target_compile_options(${target} PRIVATE -O1)
  endif()
  if(NOT arg_DISCOVERY_TIMEOUT)
    set(arg_DISCOVERY_TIMEOUT 30)
  endif()
  set(tests_file "${CMAKE_CURRENT_BINARY_DIR}/${target}_suites.cmake")
  set(include_file "${CMAKE_CURRENT_BINARY_DIR}/${target}_suites_include.cmake")
  add_custom_command(TARGET ${target} POST_BUILD
    BYPRODUCTS "${tests_file}"
    COMMAND "${CMAKE_COMMAND}"
            -D "EXECUTABLE=$<TARGET_FILE:${target}>"
            -D "WORKING_DIR=${CMAKE_CURRENT_BINARY_DIR}"
            -D "CTEST_FILE=${tests_file}"
            -D "LABELS=${arg_LABELS}"
            -D "LABELLED_SUITES=${labelled_suites}"
            -D "CASE_TIMEOUT=${arg_TIMEOUT}"
            -D "DISCOVERY_TIMEOUT=${arg_DISCOVERY_TIMEOUT}"
            -P "${PHYSICS_GTEST_SUITES_SCRIPT}"
    VERBATIM)
  # A target not built yet shows as one failing test, as with gtest_discover_tests.
  file(WRITE "${include_file}"
    "if(EXISTS \"${tests_file}\")\n"
    "  include(\"${tests_file}\")\n"
    "else()\n"
    "  add_test(${target}_NOT_BUILT ${target}_NOT_BUILT)\n"
    "endif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${include_file}")
endfunction()
