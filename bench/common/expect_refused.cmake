# expect_refused(<message> <flags>...): runs ${TOOL} ${TOOL_ARGS} <flags> the way a
# user does, and fails the test unless it exits non-zero with <message> in its
# output. Shared by the bench tools' command-line tests.
function(expect_refused message)
  execute_process(COMMAND ${TOOL} ${TOOL_ARGS} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err TIMEOUT 60)
  get_filename_component(name "${TOOL}" NAME)
  if(rc EQUAL 0)
    message(FATAL_ERROR "${name} took ${ARGN}; it should refuse it")
  endif()
  if(NOT "${out}${err}" MATCHES "${message}")
    message(FATAL_ERROR "${name} ${ARGN}: expected '${message}', got:\n${out}${err}")
  endif()
endfunction()
