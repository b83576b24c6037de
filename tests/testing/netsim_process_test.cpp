// physics-netsim as a user runs it: started as a child process (physics::testing's
// ServerProcess runs it as it runs a server: --bind, --port 0, the listening line),
// relaying a connection with its latency, and stopped with SIGTERM, after which it
// reports what it relayed.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "loopback_sockets.h"
#include "physics_testing/server_process.h"

namespace physics_testing {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

TEST(PhysicsNetsim, RelaysWithItsLatencyAndReportsOnSigterm) {
  test::Listener target_listener;
  ProcessOptions options;
  options.executable = PHYSICS_NETSIM_EXE;
  options.extra_args = {"--to",         "127.0.0.1:" + std::to_string(target_listener.port()),
                        "--latency-ms", "25",
                        "--seed",       "7"};
  ServerProcess netsim(options);
  test::Socket client = test::connect_loopback(netsim.port());
  test::Socket target = target_listener.accept(2s);
  ASSERT_TRUE(client && target);

  const std::vector<std::uint8_t> message = {'p', 'i', 'n', 'g'};
  const Clock::time_point sent = Clock::now();
  ASSERT_TRUE(client.send_all(message));
  EXPECT_EQ(target.receive(message.size(), Clock::now() + 5s), message);
  EXPECT_GE(Clock::now() - sent, 25ms);
  // The end of the stream comes after the relay has counted the bytes before it.
  client.shutdown_send();
  EXPECT_TRUE(target.receive_end(Clock::now() + 5s));

  EXPECT_EQ(netsim.stop(), 0);
  const std::string log = netsim.log();
  EXPECT_NE(log.find("1 connections; 4 bytes to the target, 0 bytes back"), std::string::npos)
      << log;
}

}  // namespace
}  // namespace physics_testing
