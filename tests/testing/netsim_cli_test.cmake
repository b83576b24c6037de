# Bad flags of physics-netsim: each exits 2 with a message that says what was wrong,
# and nothing aborts.
#   cmake -DNETSIM=path/to/physics-netsim -P netsim_cli_test.cmake

include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/expect_usage_error.cmake)

expect_usage_error("no --to" "--to is required" ${NETSIM} --latency-ms 50)
expect_usage_error("--to without a port" "HOST:PORT" ${NETSIM} --to 127.0.0.1)
expect_usage_error("--to port 0" "HOST:PORT" ${NETSIM} --to 127.0.0.1:0)
expect_usage_error("--to off loopback" "not a loopback address" ${NETSIM} --to 10.0.0.1:7777)
expect_usage_error("--to a name" "not an IP address" ${NETSIM} --to example.com:7777)
expect_usage_error("--bind off loopback" "not a loopback address"
                   ${NETSIM} --bind 0.0.0.0 --to 127.0.0.1:7777)
expect_usage_error("--listen 70000" "0 to 65535" ${NETSIM} --listen 70000 --to 127.0.0.1:7777)
expect_usage_error("--latency-ms -1" "not in range" ${NETSIM} --to 127.0.0.1:7777 --latency-ms -1)
expect_usage_error("--latency-ms abc" "abc" ${NETSIM} --to 127.0.0.1:7777 --latency-ms abc)
expect_usage_error("--jitter-ms nan" "not a finite number" ${NETSIM} --to 127.0.0.1:7777
                   --jitter-ms nan)
expect_usage_error("--bandwidth-kbps -5" "not in range" ${NETSIM} --to 127.0.0.1:7777
                   --bandwidth-kbps -5)
expect_usage_error("--stall-ms alone" "--stall-ms goes with" ${NETSIM} --to 127.0.0.1:7777
                   --stall-ms 200)
expect_usage_error("--stall-every-ms alone" "--stall-ms goes with" ${NETSIM}
                   --to 127.0.0.1:7777 --stall-every-ms 5000)
expect_usage_error("stalls back to back" "stalls.every must be longer"
                   ${NETSIM} --to 127.0.0.1:7777 --stall-ms 200 --stall-every-ms 100)
expect_usage_error("--stall-at-ms -5" "not in range" ${NETSIM} --to 127.0.0.1:7777
                   --stall-ms 200 --stall-at-ms 100,-5)
expect_usage_error("--stall-direction sideways" "--stall-direction"
                   ${NETSIM} --to 127.0.0.1:7777 --stall-direction sideways)
expect_usage_error("--bogus" "bogus" ${NETSIM} --to 127.0.0.1:7777 --bogus)

# --help names what each setting models.
execute_process(COMMAND ${NETSIM} --help RESULT_VARIABLE rc OUTPUT_VARIABLE help)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "physics-netsim --help: exit ${rc}")
endif()
foreach(text "--latency-up-ms" "--jitter-ms" "--bandwidth-kbps" "--stall-rate" "--seed")
  string(FIND "${help}" "${text}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "physics-netsim --help does not mention '${text}':\n${help}")
  endif()
endforeach()
