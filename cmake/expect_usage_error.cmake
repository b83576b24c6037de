# expect_usage_error(<what> <expected text> <command>...): runs the command the way a
# user does and fails the test unless it exits 2 with <expected text> in its output
# and without aborting. Shared by the command-line tests of the executables.
function(expect_usage_error what expected_text)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  TIMEOUT 30)
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "${what}: exit ${rc}, expected 2\n${out}${err}")
  endif()
  if(NOT "${out}${err}" MATCHES "${expected_text}")
    message(FATAL_ERROR "${what}: the message does not say '${expected_text}':\n${out}${err}")
  endif()
  if("${out}${err}" MATCHES "terminate called|Aborted")
    message(FATAL_ERROR "${what}: aborted\n${out}${err}")
  endif()
endfunction()
