# Bad flags of physics-server and physics-client: each exits 2 with a message that
# says what was wrong, and nothing aborts (physics-netbench's: bench/net).
#   cmake -DSERVER=... -DCLIENT=... -P cli_flags_test.cmake

include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/expect_usage_error.cmake)

expect_usage_error("server --port 99999" "0 to 65535" ${SERVER} --port 99999)
expect_usage_error("server --tick-rate abc" "Failed parsing abc" ${SERVER} --tick-rate abc)
expect_usage_error("server --tick-rate -5" "not in range" ${SERVER} --tick-rate -5)
# The --tick-rate range is scene/scene.h's, both ends included: just outside it the
# flag is refused; at either end it passes, and the error is the next bad flag's.
expect_usage_error("server --tick-rate 1000.001" "not in range 0.001000 to 1000.000000"
                   ${SERVER} --tick-rate 1000.001)
expect_usage_error("server --tick-rate 0.00099" "not in range" ${SERVER} --tick-rate 0.00099)
expect_usage_error("server --tick-rate 1000 passes" "^--log-format: xml"
                   ${SERVER} --tick-rate 1000 --log-format xml)
expect_usage_error("server --tick-rate 0.001 passes" "^--log-format: xml"
                   ${SERVER} --tick-rate 0.001 --log-format xml)
expect_usage_error("server --lockstep-pace slow" "--lockstep-pace" ${SERVER} --lockstep-pace slow)
expect_usage_error("server --log-format xml" "--log-format" ${SERVER} --log-format xml)
expect_usage_error("server --lockstep-players 0" "--lockstep-players" ${SERVER} --lockstep-players 0)
expect_usage_error("server --metrics-port 70000" "0 to 65535" ${SERVER} --metrics-port 70000)
expect_usage_error("server --ws-port 70000" "0 to 65535" ${SERVER} --ws-port 70000)
expect_usage_error("server --metrics-bind nowhere" "not an IP address" ${SERVER}
                   --metrics-bind nowhere)
expect_usage_error("server --max-players-per-address -1" "--max-players-per-address" ${SERVER}
                   --max-players-per-address -1)
expect_usage_error("AGONES_SDK_HTTP_PORT=abc" "AGONES_SDK_HTTP_PORT"
                   ${CMAKE_COMMAND} -E env AGONES_SDK_HTTP_PORT=abc ${SERVER} --port 0)

expect_usage_error("client --port 99999" "1 to 65535" ${CLIENT} --port 99999)
expect_usage_error("client --bogus" "bogus" ${CLIENT} --bogus)
expect_usage_error("client --seat -1" "--seat" ${CLIENT} --seat -1)
expect_usage_error("client --accel nan,0" "finite" ${CLIENT} --accel nan,0)
string(REPEAT "x" 257 long_payload)
expect_usage_error("client --game-message of 257 bytes" "at most 256 bytes; this one has 257"
                   ${CLIENT} --game-message ${long_payload})
expect_usage_error("client 5 game messages" "at most 4 game messages" ${CLIENT}
                   --game-message a --game-message b --game-message c --game-message d
                   --game-message e)
expect_usage_error("client --message-every-ms 0" "--message-every-ms: Value 0 not in range"
                   ${CLIENT} --game-message a --message-every-ms 0)
expect_usage_error("client --message-every-ms -5" "--message-every-ms" ${CLIENT}
                   --game-message a --message-every-ms -5)
expect_usage_error("client --message-every-ms alone" "requires --game-message" ${CLIENT}
                   --message-every-ms 100)
expect_usage_error("client --game-message --spectate" "excludes" ${CLIENT} --spectate
                   --game-message a)

# --help says how --max-clients and the scene's room go together, and names the
# lockstep lobby flags.
execute_process(COMMAND ${SERVER} --help RESULT_VARIABLE rc OUTPUT_VARIABLE help)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "server --help: exit ${rc}")
endif()
foreach(text "ERROR_NO_SPAWN" "fits 58" "--lockstep-players" "--lockstep-max-timeouts"
        "--metrics-port" "--metrics-bind" "--log-format" "--max-players-per-address" "--ws-port"
        "acknowledges none of the snapshots")
  string(FIND "${help}" "${text}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "server --help does not mention '${text}':\n${help}")
  endif()
endforeach()
