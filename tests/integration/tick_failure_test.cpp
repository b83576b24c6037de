// A tick that throws (std::bad_alloc inside the step, say) leaves the one world the
// server owns half stepped. The server must say why and shut down, telling its
// clients, instead of either dying with every match or serving a world no replay
// reproduces. ServerConfig::on_tick is the fault injector: it runs inside the tick.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>

#include "harness.h"

namespace itest {
namespace {

// Throws from the first tick after arm(), and remembers which tick that was.
struct Fault {
  std::atomic<bool> armed{false};
  std::atomic<std::uint64_t> failed_at{0};
  server::ServerConfig config(bool lockstep) {
    server::ServerConfig config = test_config(lockstep);
    config.on_tick = [this](std::uint64_t tick, std::uint64_t) {
      if (!armed) return;
      failed_at = tick;
      throw std::runtime_error("injected fault");
    };
    return config;
  }
};

// The client hears ERROR_SHUTTING_DOWN; the stats name the failure; no tick after
// the failing one is stepped.
void expect_stopped_at_failure(RunningServer& server, client::Client& player, Fault& fault) {
  auto error = player.next_error(5s);
  ASSERT_TRUE(error.has_value()) << player.last_error().to_string();
  EXPECT_EQ(error->code, client::ErrorCode::ShuttingDown);
  EXPECT_TRUE(error->fatal);
  ASSERT_TRUE(eventually([&] { return !server.stats().tick_failure.empty(); }));
  const server::ServerStats stats = server.stats();
  EXPECT_EQ(stats.tick_failure, "injected fault");
  EXPECT_TRUE(stats.shutting_down);
  EXPECT_NE(fault.failed_at.load(), 0u);
  EXPECT_EQ(stats.current_tick, fault.failed_at.load());
}

TEST(TickFailure, AFixedRateTickThatThrowsShutsTheServerDownWithAReason) {
  Fault fault;
  RunningServer server(fault.config(false), scene::default_scene());
  client::Client player(server.client_config("player"));
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  fault.armed = true;
  expect_stopped_at_failure(server, player, fault);
}

TEST(TickFailure, ALockstepTickThatThrowsShutsTheServerDownWithAReason) {
  Fault fault;
  RunningServer server(fault.config(true), scene::default_scene());
  client::Client player(server.client_config("player"));
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  ASSERT_TRUE(player.send_input(player.welcome().current_tick + 1, 1.0, 0.0));
  ASSERT_TRUE(player.wait_for_snapshot(
      3s, [&](const client::Snapshot& s) { return s.tick >= player.welcome().current_tick + 1; }));
  fault.armed = true;
  for (std::uint64_t tick = player.welcome().current_tick + 2;
       tick <= player.welcome().current_tick + 6; ++tick) {
    if (!player.send_input(tick, 1.0, 0.0)) break;
  }
  expect_stopped_at_failure(server, player, fault);
}

TEST(TickFailure, AnObserverThatReturnsLeavesTheServerServing) {
  std::atomic<std::uint64_t> observed{0};
  server::ServerConfig config = test_config();
  config.on_tick = [&observed](std::uint64_t tick, std::uint64_t) { observed = tick; };
  RunningServer server(config, scene::default_scene());
  client::Client player(server.client_config("player"));
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  ASSERT_TRUE(player.wait_for_snapshot(3s, [](const client::Snapshot& s) { return s.tick >= 10; }));
  EXPECT_GE(observed.load(), 10u);
  EXPECT_TRUE(server.stats().tick_failure.empty());
  EXPECT_FALSE(server.stats().shutting_down);
}

}  // namespace
}  // namespace itest
