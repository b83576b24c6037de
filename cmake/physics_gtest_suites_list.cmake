# Run after a test executable is built (cmake -P, from physics_gtest_suites): lists its
# GoogleTest suites and writes CTEST_FILE, one ctest test per suite.
# Inputs: EXECUTABLE, WORKING_DIR, CTEST_FILE, LABELS (a list), LABELLED_SUITES (a list
# of "Suite=label,label": labels of those suites only), CASE_TIMEOUT (seconds per test
# case, may be empty), DISCOVERY_TIMEOUT.
execute_process(
  COMMAND "${EXECUTABLE}" --gtest_list_tests
  WORKING_DIRECTORY "${WORKING_DIR}"
  TIMEOUT ${DISCOVERY_TIMEOUT}
  OUTPUT_VARIABLE listing
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${EXECUTABLE} --gtest_list_tests failed (${result}):\n${listing}")
endif()

# The listing: a suite line ("Suite." or "Prefix/Suite/0.  # TypeParam = ..."), then
# its cases indented by two spaces ("  Case/1  # GetParam() = ...").
string(REPLACE ";" "\\;" listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")
set(suites "")
set(suite "")
foreach(line IN LISTS lines)
  string(REGEX REPLACE " *#.*$" "" line "${line}")
  if(line MATCHES "^([^ ].*)\\.$")
    set(suite "${CMAKE_MATCH_1}")
    if(suite MATCHES "(^|/)DISABLED_")
      set(suite "")
    endif()
  elseif(suite AND line MATCHES "^  ([^ ].*)$")
    if(NOT CMAKE_MATCH_1 MATCHES "^DISABLED_")
      if(NOT DEFINED count_${suite})
        list(APPEND suites "${suite}")
        set(count_${suite} 0)
      endif()
      math(EXPR count_${suite} "${count_${suite}} + 1")
    endif()
  endif()
endforeach()

foreach(entry IN LISTS LABELLED_SUITES)
  string(REGEX MATCH "^([^=]+)=(.*)$" matched "${entry}")
  string(REPLACE "," ";" extra_${CMAKE_MATCH_1} "${CMAKE_MATCH_2}")
  # A suite named in the CMakeLists that the executable does not have is a typo there.
  if(NOT DEFINED count_${CMAKE_MATCH_1})
    message(FATAL_ERROR "${EXECUTABLE} has no suite ${CMAKE_MATCH_1} to label")
  endif()
endforeach()

set(script "")
foreach(suite IN LISTS suites)
  set(name "${suite}.*")
  set(suite_labels ${LABELS} ${extra_${suite}})
  string(APPEND script
    "add_test([==[${name}]==] [==[${EXECUTABLE}]==] [==[--gtest_filter=${name}]==])\n"
    "set_tests_properties([==[${name}]==] PROPERTIES WORKING_DIRECTORY [==[${WORKING_DIR}]==]")
  if(suite_labels)
    string(APPEND script " LABELS [==[${suite_labels}]==]")
  endif()
  if(CASE_TIMEOUT)
    math(EXPR timeout "${CASE_TIMEOUT} * ${count_${suite}}")
    string(APPEND script " TIMEOUT ${timeout}")
  endif()
  string(APPEND script ")\n")
endforeach()
file(WRITE "${CTEST_FILE}" "${script}")
