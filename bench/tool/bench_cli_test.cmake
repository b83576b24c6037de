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

# Velocity iterations are a grid axis of their own, and bad counts are refused.
expect_refused("not in range" --velocity-iterations 0)
expect_refused("not in range" --velocity-iterations 65)
expect_refused("not in range" --timeline-window 0)

# The timeline: one row per window of each run, the last window taking what is left
# (the projectile scenes run 120 steps at 60 Hz: windows of 50, 50 and 20 steps;
# "projectile" picks projectile and projectile-friction, so 4 runs).
set(timeline_file ${CMAKE_CURRENT_BINARY_DIR}/bench_cli_timeline.csv)
file(REMOVE ${timeline_file})
execute_process(COMMAND ${BENCH} --scenes projectile --engines ours --integrators exact
                        --substeps 1 --iterations 4 --velocity-iterations 4,8
                        --timeline ${timeline_file} --timeline-window 50
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "physics-bench --timeline failed (${rc}): ${err}")
endif()
foreach(label 4v/4p 8v/4p)
  if(NOT out MATCHES ",exact,1,${label},on,")
    message(FATAL_ERROR "physics-bench ran no ${label} row:\n${out}")
  endif()
endforeach()
file(STRINGS ${timeline_file} timeline)
list(LENGTH timeline lines)
if(NOT lines EQUAL 13)
  message(FATAL_ERROR "expected a header and 3 windows for each of 4 runs, got:\n${timeline}")
endif()
list(GET timeline 0 header)
if(NOT header STREQUAL "scene,engine,iterations,sleeping,end_s,steps,awake,ms_mean,cpu_ms_mean")
  message(FATAL_ERROR "unexpected timeline header: ${header}")
endif()
foreach(expected "projectile,ours,4v/4p,on,0.833333,50,1," "projectile,ours,4v/4p,on,2,20,1,"
                 "projectile,ours,8v/4p,on,1.66667,50,1,")
  string(FIND "${timeline}" "${expected}" found)
  if(found EQUAL -1)
    message(FATAL_ERROR "timeline has no row starting '${expected}':\n${timeline}")
  endif()
endforeach()

# A bad output path fails before any scene runs (--ratios was found bad only after
# the runs, which can take many minutes): no CSV row may reach stdout first.
set(TOOL_ARGS)  # without --list, which would exit before opening anything
expect_refused("cannot write" --scenes projectile --engines ours --csv /nonexistent/dir/c.csv)
foreach(flag --ratios --timeline)
  execute_process(COMMAND ${BENCH} --scenes projectile --engines ours ${flag} /nonexistent/dir/x.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
  if(rc EQUAL 0 OR NOT err MATCHES "cannot write")
    message(FATAL_ERROR "physics-bench ${flag} /nonexistent/dir/x.csv: expected 'cannot write' and a failure, got ${rc}:\n${err}")
  endif()
  if(out MATCHES "projectile,ours")
    message(FATAL_ERROR "physics-bench ${flag} with a bad path ran scenes first:\n${out}")
  endif()
endforeach()
