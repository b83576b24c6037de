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

# The baseline engine (another revision's core, PHYSICS_BASELINE_CORE): it runs with
# our settings, gets a row of its own and a ratio against ours, and reports its state
# hash as ours does. A build without it says how to get it and runs the rest.
set(ratios_file ${CMAKE_CURRENT_BINARY_DIR}/bench_cli_ratios.csv)
execute_process(COMMAND ${BENCH} --scenes projectile --engines ours,baseline --integrators exact
                        --substeps 1 --iterations 4 --ratios ${ratios_file}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "physics-bench --engines ours,baseline failed (${rc}): ${err}")
endif()
if(HAVE_BASELINE)
  file(READ ${ratios_file} ratios)
  foreach(engine ours baseline)
    if(NOT out MATCHES "\nprojectile,${engine},exact,1,[^\n]*state_hash=[0-9a-f]+\n")
      message(FATAL_ERROR "no ${engine} row with a state hash:\n${out}")
    endif()
  endforeach()
  if(NOT ratios MATCHES "\nprojectile,on,cpu_mean,[^,]*,baseline,")
    message(FATAL_ERROR "no baseline/ours ratio:\n${ratios}")
  endif()
else()
  if(NOT err MATCHES "baseline is not built in \\(configure with -DPHYSICS_BASELINE_CORE=DIR\\)")
    message(FATAL_ERROR "physics-bench should say how to build the baseline:\n${err}")
  endif()
  if(NOT out MATCHES "\nprojectile,ours,exact,1,[^\n]*state_hash=[0-9a-f]+\n")
    message(FATAL_ERROR "no row of ours with a state hash:\n${out}")
  endif()
endif()

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

# Runs that take turns (--interleave) give every engine the same steps as runs one
# after another: the same rows but for the times, and the same timeline windows.
# 7 steps a turn does not divide the scenes' 120 and 600 steps, nor the 50-step
# windows, so a step lost or repeated at a turn's end shows.
expect_refused("not in range" --interleave -1)
cmake_policy(SET CMP0007 NEW)  # the rows' empty fields stay list elements
set(run_args --scenes projectile bounce-e0.5 --engines ours,box2d,chipmunk --peers-everywhere
             --integrators exact,semi-implicit-euler --substeps 1 --iterations 4
             --timeline-window 50)
foreach(mode one_after_another taking_turns)
  set(extra)
  if(mode STREQUAL "taking_turns")
    set(extra --interleave 7)
  endif()
  set(timeline_file ${CMAKE_CURRENT_BINARY_DIR}/bench_cli_${mode}.csv)
  execute_process(COMMAND ${BENCH} ${run_args} ${extra} --timeline ${timeline_file}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "physics-bench ${extra} failed (${rc}): ${err}")
  endif()
  # Each row without its times: columns 9-15 and 24-30 (ms_*, cpu_ms_*, prof_*).
  # (The notes' ';' would split a CMake list: made '|' first.)
  string(REPLACE ";" "|" out "${out}")
  string(REPLACE "\n" ";" rows "${out}")
  set(kept_${mode})
  foreach(row IN LISTS rows)
    string(REPLACE "," ";" fields "${row}")
    list(LENGTH fields count)
    if(count LESS 32)
      continue()
    endif()
    list(GET fields 0 1 2 3 4 5 6 7 8 16 17 18 19 20 21 22 23 31 untimed)
    list(JOIN untimed "," untimed)
    list(APPEND kept_${mode} "${untimed}")
  endforeach()
  # Each timeline row's scene, engine, iterations, sleeping, end, steps and awake.
  file(STRINGS ${timeline_file} windows)
  set(windows_${mode})
  foreach(window IN LISTS windows)
    string(REGEX MATCH "^([^,]*,){7}" start "${window}")
    list(APPEND windows_${mode} "${start}")
  endforeach()
endforeach()
list(LENGTH kept_one_after_another rows)
if(rows LESS 6)
  message(FATAL_ERROR "expected at least 6 runs, got ${rows}:\n${kept_one_after_another}")
endif()
if(NOT kept_one_after_another STREQUAL kept_taking_turns)
  message(FATAL_ERROR "--interleave changed the runs' results:\none after another:\n"
                      "${kept_one_after_another}\ntaking turns:\n${kept_taking_turns}")
endif()
if(NOT windows_one_after_another STREQUAL windows_taking_turns)
  message(FATAL_ERROR "--interleave changed the timeline's windows:\n"
                      "${windows_one_after_another}\n${windows_taking_turns}")
endif()

# Peers asked for on a scene they do not run on: said on stderr, with the way to run
# them. Chipmunk's banner stays off stdout, where the CSV goes.
execute_process(COMMAND ${BENCH} --scenes projectile --engines ours,box2d,chipmunk
                        --integrators exact --substeps 1 --iterations 4
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "physics-bench --engines ours,box2d,chipmunk failed (${rc}): ${err}")
endif()
if(NOT err MATCHES "run on their own scenes only \\(add --peers-everywhere[^\n]*ours alone on: projectile, projectile-friction\n")
  message(FATAL_ERROR "physics-bench should say the peers did not run on projectile:\n${err}")
endif()
if(NOT out MATCHES "^scene,engine,")
  message(FATAL_ERROR "stdout should start with the CSV header:\n${out}")
endif()
execute_process(COMMAND ${BENCH} --scenes projectile --engines ours,chipmunk --peers-everywhere
                        --integrators exact --substeps 1 --iterations 4
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "physics-bench --engines ours,chipmunk failed (${rc}): ${err}")
endif()
if(out MATCHES "Chipmunk v" OR NOT out MATCHES "^scene,engine,")
  message(FATAL_ERROR "stdout should hold the CSV alone, without Chipmunk's banner:\n${out}")
endif()
