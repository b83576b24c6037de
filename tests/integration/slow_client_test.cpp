// A client that never reads: the server keeps serving the others, keeps that
// client's queue bounded (the newest snapshot replaces unsent ones), and finally
// drops it. Snapshots of 3,000 bodies (about 120 kB each) fill the socket buffers
// in well under a second, so the bound is reached quickly.
#include <gtest/gtest.h>

#include "harness.h"
#include "test_scenes.h"

namespace itest {
namespace {

TEST(SlowClient, NeverReadingClientIsBoundedThenDroppedWhileOthersAreServed) {
  server::ServerConfig config = test_config();
  config.idle_timeout = 1000ms;
  RunningServer server(config, crowd_scene(3000));

  client::Client good(server.client_config("good"));
  ASSERT_TRUE(good.connect(3s)) << good.last_error().to_string();

  RawPeer sleeper(server.port());
  sleeper.set_receive_buffer(4096);
  ASSERT_TRUE(sleeper.send(hello_message("never-reads")));

  // The sleeper keeps talking (so it is not idle) but never reads; only the write
  // stall can get it dropped. It sends inputs, which have no reply (a Ping's Pong
  // would pile up too). Meanwhile the good client must keep getting ticks.
  std::uint64_t last_tick = 0;
  std::size_t good_snapshots = 0;
  const auto was_dropped = [&] {
    const auto stats = server.stats();
    return dropped(stats, server::DropReason::TooSlow) + dropped(stats, server::DropReason::Idle) >
           0;
  };
  const auto deadline = std::chrono::steady_clock::now() + 15s;
  while (!was_dropped() && std::chrono::steady_clock::now() < deadline) {
    sleeper.send(input_message(last_tick + 1, 0.0, 0.0));
    good.send_input(last_tick + 1, 0.0, 0.0);  // the good client is not idle either
    auto snapshot = good.next_snapshot(2s);
    ASSERT_TRUE(snapshot.has_value())
        << "the good client stalled: " << good.last_error().to_string();
    EXPECT_GT(snapshot->tick, last_tick);
    last_tick = snapshot->tick;
    ++good_snapshots;
  }
  ASSERT_TRUE(was_dropped()) << "the never-reading client was not dropped";
  const server::ServerStats stats = server.stats();
  EXPECT_EQ(dropped(stats, server::DropReason::TooSlow), 1u)
      << "dropped for being idle instead of for not reading";
  // Its backlog was bounded: unsent snapshots were replaced, not queued.
  EXPECT_GT(stats.dropped_snapshots, 0u);
  // No session's queue ever held more than the bound (plus the one being written).
  EXPECT_LE(stats.peak_queued_snapshots, config.max_queued_snapshots + 1);
  EXPECT_GT(good_snapshots, 10u);
  EXPECT_EQ(good.state(), client::ConnectionState::Connected);
  EXPECT_TRUE(eventually([&] { return server.stats().open_connections == 1; }));
  // (The sleeper's own view of the close is not checked: megabytes it never read are
  // still in flight to it; the server side above is what matters.)
  EXPECT_EQ(check_server_serves(server), "");
}

}  // namespace
}  // namespace itest
