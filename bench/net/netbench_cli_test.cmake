# Runs physics-netbench the way a user does: each bad flag exits 2 with a message
# that says what was wrong, and nothing aborts; a short run with one bot prints its
# table row and writes its CSV.
#   cmake -DNETBENCH=path/to/physics-netbench -DWORK=dir -P netbench_cli_test.cmake

include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/expect_usage_error.cmake)

expect_usage_error("--tick-rate -5" "not in range" ${NETBENCH} --tick-rate -5)
expect_usage_error("--tick-rate abc" "Failed parsing abc" ${NETBENCH} --tick-rate abc)
expect_usage_error("--bots 0" "--bots" ${NETBENCH} --bots 0)
expect_usage_error("--bots -3" "--bots" ${NETBENCH} --bots -3)
expect_usage_error("--duration -1" "--duration" ${NETBENCH} --duration -1)
expect_usage_error("--encodings zip" "--encodings" ${NETBENCH} --encodings zip)
expect_usage_error("--prediction-bots 0" "--prediction-bots" ${NETBENCH} --prediction --prediction-bots 0)
expect_usage_error("--input-change-ms -1" "--input-change-ms" ${NETBENCH} --input-change-ms -1)
expect_usage_error("--snapshot-intervals 0" "--snapshot-intervals" ${NETBENCH} --snapshot-intervals 0)
expect_usage_error("--scenes missing" "missing.textproto" ${NETBENCH} --scenes ${WORK}/missing.textproto)

# One bot on the built-in scene for a fraction of a second (inputs not held: 0), a
# snapshot every second tick: the row says it joined, and the CSV has the header and
# that row.
set(csv ${WORK}/netbench-cli.csv)
file(REMOVE ${csv})
execute_process(COMMAND ${NETBENCH} --bots 1 --duration 0.3 --encodings full
                        --snapshot-intervals 2 --csv ${csv}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "physics-netbench --bots 1 failed (${rc}):\n${out}${err}")
endif()
if(NOT out MATCHES "\\| [^|]+ \\| full \\| 0 \\| 2 \\| 1 \\(1\\) \\|")
  message(FATAL_ERROR "physics-netbench: no row of one joined bot:\n${out}${err}")
endif()
file(STRINGS ${csv} rows)
list(LENGTH rows count)
if(NOT count EQUAL 2)
  message(FATAL_ERROR "physics-netbench --csv: ${count} lines, expected a header and one row")
endif()
list(GET rows 0 header)
if(NOT header MATCHES "^scene,encoding,still,clients_asked,clients_joined,")
  message(FATAL_ERROR "physics-netbench --csv: unexpected header '${header}'")
endif()
list(GET rows 1 row)
if(NOT row MATCHES ",0,2$")
  message(FATAL_ERROR "physics-netbench --csv: the row does not end in input_change_ms 0 and snapshot_interval 2: '${row}'")
endif()
