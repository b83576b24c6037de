# Every executable given in TOOLS (a list of paths) exits 2, saying which flag, when
# given a flag it does not know, and does not abort: the README promises exit code 2
# on a bad flag for all of them.
#   cmake "-DTOOLS=path1;path2" -P unknown_flag_test.cmake
include(${CMAKE_CURRENT_LIST_DIR}/../cmake/expect_usage_error.cmake)
if(NOT TOOLS)
  message(FATAL_ERROR "no TOOLS given")
endif()
foreach(tool IN LISTS TOOLS)
  get_filename_component(name "${tool}" NAME)
  expect_usage_error("${name} --no-such-flag" "no-such-flag" "${tool}" --no-such-flag)
endforeach()
