// The predicting bots of physics-client --bots and physics-netbench (client/load.h)
// on a real server: held inputs are rolled back only when another bot's change is
// confirmed, and every rendered frame's CPU time is counted.
#include <gtest/gtest.h>

#include <chrono>

#include "client/load.h"
#include "harness.h"

namespace {

using namespace std::chrono_literals;

client::LoadReport two_predicting_bots(std::chrono::milliseconds input_change_interval) {
  itest::RunningServer server(itest::test_config(false), scene::default_scene());
  client::LoadConfig load;
  load.client.port = server.port();
  load.client.name = "held";
  load.bots = 2;
  load.predict = true;
  load.input_change_interval = input_change_interval;
  load.settle = 500ms;
  load.duration = 2s;
  return client::run_load(load);
}

TEST(PredictingBots, HeldInputsRollBackOnlyAtTheOtherBotsChanges) {
  const client::LoadReport held = two_predicting_bots(500ms);
  ASSERT_EQ(held.bots_connected, 2) << (held.failures.empty() ? "" : held.failures.front());
  EXPECT_EQ(held.desyncs, 0u);
  // The other bot changes twice a second: at most that many rollbacks, and a few
  // more where one snapshot's ticks straddle a change (never one a tick).
  EXPECT_LE(held.rollbacks_per_second, 5.0);
  // Every tick a frame, each with the CPU time its thread spent.
  EXPECT_GT(held.frames, 60u);
  EXPECT_GT(held.frame_cpu_ms_p99, 0.0);
  EXPECT_GE(held.frame_cpu_ms_p99, held.frame_cpu_ms_median);
}

TEST(PredictingBots, InputsChangedEveryTickRollBackEveryTick) {
  const client::LoadReport turning = two_predicting_bots(0ms);
  ASSERT_EQ(turning.bots_connected, 2)
      << (turning.failures.empty() ? "" : turning.failures.front());
  EXPECT_GT(turning.rollbacks_per_second, 20.0);
}

}  // namespace
