// Slow and stopped readers. A client that never reads: the server keeps serving
// the others, holds at most that client's window of snapshots (it skips ticks
// instead of queueing them), and drops it as too slow once a write to it has made
// no progress for idle_timeout. It asks for full snapshots of 3,000 bodies (about
// 120 kB each), which fill the socket buffers at once. A client that reads ten
// snapshots a second sees state no older than its window of its own reads.
#include <gtest/gtest.h>

#include <cstdio>
#include <thread>
#include <vector>

#include "harness.h"
#include "test_scenes.h"

namespace itest {
namespace {

TEST(SlowClient, NeverReadingClientHoldsItsWindowWhileOthersAreServedThenIsDroppedAsTooSlow) {
  server::ServerConfig config = test_config();
  // The sleeper talks every tick, so it is never idle: only a write to it that makes
  // no progress for this long drops it. 4 s lets a slow build (ThreadSanitizer steps
  // this crowd at about 25 ticks a second) step the 60 ticks below first.
  config.idle_timeout = 4000ms;
  // With the OS default (megabytes) the kernel would take the sleeper's whole window
  // and no write would ever stall; 16 KiB holds less than one of its snapshots.
  config.socket_send_buffer_bytes = 16384;
  RunningServer server(config, crowd_scene(3000));

  client::Client good(server.client_config("good"));
  ASSERT_TRUE(good.connect(3s)) << good.last_error().to_string();

  RawPeer sleeper(server.port());
  sleeper.set_receive_buffer(4096);
  physics::wire::ClientMessage hello = hello_message("never-reads");
  hello.mutable_hello()->mutable_view()->set_encoding(physics::wire::ENCODING_FULL);
  ASSERT_TRUE(sleeper.send(hello));

  // The sleeper keeps talking (so it is not idle) but never reads. Meanwhile the
  // good client must keep getting ticks: 60 of them, however slow the build. A
  // server held up by the sleeper would send it none at all; 5 s between two of its
  // snapshots leaves a ThreadSanitizer build on a busy machine (a few ticks a
  // second) room, while staying under the 20 s the sleeper's drop is awaited.
  std::uint64_t last_tick = 0;
  std::size_t good_snapshots = 0;
  auto serve_good_once = [&] {
    sleeper.send(input_message(last_tick + 1, 0.0, 0.0));
    good.send_input(last_tick + 1, 0.0, 0.0);  // its inputs make every tick news
    auto snapshot = good.next_snapshot(5s);
    ASSERT_TRUE(snapshot.has_value())
        << "the good client stalled: " << good.last_error().to_string();
    EXPECT_GT(snapshot->tick, last_tick);
    last_tick = snapshot->tick;
    ++good_snapshots;
  };
  const auto deadline = std::chrono::steady_clock::now() + 40s;
  while (good_snapshots < 60 && std::chrono::steady_clock::now() < deadline) {
    serve_good_once();
    if (HasFatalFailure()) return;
  }
  const server::ServerStats stats = server.stats();
  // Its backlog was bounded: due snapshots were skipped, not queued (every due tick
  // past its window of 12: at least 20 of the 60), and the server never held more
  // than 12 for any session.
  EXPECT_EQ(good_snapshots, 60u);
  EXPECT_GE(stats.skipped_snapshots, 20u);
  EXPECT_LE(stats.peak_queued_snapshots, 12u);
  EXPECT_EQ(good.state(), client::ConnectionState::Connected);

  // Its writes have stalled since it joined (its Welcome alone is larger than the
  // buffers): dropped as too slow, never as idle, one timeout after the stall; that
  // is awaited for 5 timeouts while the good client is served on.
  const auto drop_deadline = std::chrono::steady_clock::now() + 5 * config.idle_timeout;
  while (dropped(server.stats(), server::DropReason::TooSlow) == 0 &&
         std::chrono::steady_clock::now() < drop_deadline) {
    serve_good_once();
    if (HasFatalFailure()) return;
  }
  EXPECT_EQ(dropped(server.stats(), server::DropReason::TooSlow), 1u);
  EXPECT_EQ(dropped(server.stats(), server::DropReason::Idle), 0u);
  EXPECT_LE(server.stats().peak_queued_snapshots, 12u);
  EXPECT_TRUE(eventually([&] { return server.stats().connected_clients == 1u; }));
  // The sleeper then reads through what the kernel still holds for it before it sees
  // the close; under AddressSanitizer that took over 3 s in one run of four. A server
  // that never closed it fails this at any deadline.
  EXPECT_TRUE(sleeper.wait_closed(10s));
  const std::uint64_t before = last_tick;
  serve_good_once();
  EXPECT_GT(last_tick, before);
  EXPECT_EQ(good.state(), client::ConnectionState::Connected);
  EXPECT_EQ(check_server_serves(server), "");
}

// The window bounds what a slow reader can fall behind: it holds at most `window`
// snapshots it has not taken, so what it takes was made at most `window` of its own
// reads ago, plus one read for the round trip of its acknowledgement. Counted in
// reads, not seconds, so that a loaded machine that delays the reader changes
// nothing: the snapshot taken at read i is newer than the server's tick at read
// i - window - 1. The age in seconds at 10 reads a second is printed.
TEST(SlowClient, AReaderTakingTenSnapshotsASecondStaysWithinItsWindow) {
  RunningServer server(test_config(), scene::default_scene());
  client::ClientConfig config = server.client_config("ten-a-second");
  config.view.state_hash = true;
  client::Client reader(config);
  ASSERT_TRUE(reader.connect(3s)) << reader.last_error().to_string();
  const double tick_rate = reader.welcome().tick_rate;
  const std::uint32_t window = reader.welcome().view.window;
  ASSERT_EQ(window, 12u);
  std::vector<std::uint64_t> server_tick_at_read;
  double worst_age = 0.0;
  std::size_t behind = 0;
  for (int i = 0; i < 40; ++i) {
    std::this_thread::sleep_for(100ms);
    auto snapshot = reader.next_snapshot(2s);
    ASSERT_TRUE(snapshot.has_value()) << reader.last_error().to_string();
    reader.send_input(snapshot->tick + 1, 1.0, 0.0);  // its inputs make every tick news
    const std::uint64_t now = server.stats().current_tick;
    server_tick_at_read.push_back(now);
    const double age = static_cast<double>(now - snapshot->tick) / tick_rate;
    if (i >= 15) worst_age = std::max(worst_age, age);  // after the first window is drained
    const std::size_t reads = server_tick_at_read.size();
    if (reads > window + 1 && snapshot->tick < server_tick_at_read[reads - 1 - (window + 1)]) {
      ++behind;
    }
  }
  std::printf("worst age of a snapshot taken: %.3f s (window %u, 10 reads/s)\n", worst_age, window);
  EXPECT_EQ(behind, 0u) << "snapshots taken that were made more than window + 1 reads ago";
  EXPECT_GT(server.stats().skipped_snapshots, 0u);
  EXPECT_LE(server.stats().peak_queued_snapshots, window);
}

}  // namespace
}  // namespace itest
