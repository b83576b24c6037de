# Runs physics-bench the way a user does and checks that bad flags get a clear error
# and a non-zero exit, and good ones are taken.
#   cmake -DBENCH=path/to/physics-bench -P bench_cli_test.cmake

set(TOOL ${BENCH})
set(TOOL_ARGS --list)
include(${CMAKE_CURRENT_LIST_DIR}/../common/expect_refused.cmake)

# CLI::Range alone lets NaN through (every comparison with it is false).
foreach(bad nan inf -1 101 abc 0.5x)
  expect_refused("friction must be a number from 0 to 100, not ${bad}" --pile-friction "${bad}")
endforeach()
expect_refused("required" --pile-friction "")
expect_refused("not in range" --rain-count 0)

execute_process(COMMAND ${BENCH} --list --pile-friction 0,0.2,1 --rain-count 100
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "physics-bench --list --pile-friction 0,0.2,1 failed (${rc}): ${err}")
endif()
foreach(scene pile-rain-100-mu0 pile-rain-100-mu0.2 pile-rain-100-mu1 rain-100)
  if(NOT out MATCHES "(^|\n)${scene}\n")
    message(FATAL_ERROR "physics-bench --list does not name ${scene}:\n${out}")
  endif()
endforeach()
if(out MATCHES "pile-rain-100-mu0.5\n")
  message(FATAL_ERROR "--pile-friction should replace the default friction:\n${out}")
endif()
