# Runs physics-settle the way a user does: bad flags get a clear error and a
# non-zero exit; a small pile runs and reports what the tool promises.
#   cmake -DSETTLE=path/to/physics-settle -P settle_cli_test.cmake

set(TOOL ${SETTLE})
set(TOOL_ARGS --circles 10 --seconds 1)
include(${CMAKE_CURRENT_LIST_DIR}/../common/expect_refused.cmake)

# CLI::Range alone lets NaN through (every comparison with it is false).
foreach(bad nan inf -1 11 abc 0.5x)
  expect_refused("friction must be a number from 0 to 10, not ${bad}" --mu "${bad}")
endforeach()
foreach(bad nan inf 1 10001 abc)
  expect_refused("width must be a number from 1.2 to 10000, not ${bad}" --width "${bad}")
endforeach()
expect_refused("not in range" --per-row -1)
expect_refused("--per-row 20 needs --width of at least 24.0 m, not 20" --per-row 20 --width 20)
expect_refused("not in range" --circles 0)
expect_refused("not in range" --seconds 0)

# The 16,000-circle pile's layout, a few rows of it: every circle lands and sleeps, and the
# report names the overlap counts.
execute_process(COMMAND ${SETTLE} --width 100 --circles 160 --per-row 80 --mu 0.5 --seconds 10
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "physics-settle --per-row 80 failed (${rc}): ${err}")
endif()
foreach(line "asleep from [0-9.]+ s" "worst overlap [0-9.e-]+ m"
        "pairs over 5 mm [0-9]+ \\([0-9]+ side by side\\), over 1 cm [0-9]+ \\([0-9]+ side by side\\)")
  if(NOT out MATCHES "${line}")
    message(FATAL_ERROR "physics-settle output lacks '${line}':\n${out}")
  endif()
endforeach()
