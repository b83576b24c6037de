// A slow reader against the window (docs/PROTOCOL.md 3.5 and 5.8), socket-free: the
// server sends a snapshot on each 60 Hz tick while the window is open; the reader
// takes one every 100 ms, oldest first, and acknowledges it. What it takes is never
// older than the window in force allows: window / 10 s, plus a tick. A window the
// Hello asked for holds that delay at 12 / 10 s; a window left to follow the round
// trip counts the reader's own queue in the round trip and grows to the cap, 64, and
// the delay with it, to 6.4 s: the bound 3.5 gives, and no further.
#include <gtest/gtest.h>

#include <algorithm>
#include <deque>

#include "ack_window.h"

namespace server {
namespace {

using namespace std::chrono_literals;

struct SlowReaderRun {
  std::uint32_t largest_window = 0;
  double worst_age_s = 0.0;  // over the last 10 s of 30
};

SlowReaderRun read_slowly(AckWindow& window) {
  const std::chrono::nanoseconds tick(16'666'667);
  const AckWindow::time_point t0 = AckWindow::time_point{} + 100s;
  std::deque<std::uint64_t> unread;  // sent, in order
  SlowReaderRun run;
  const std::uint64_t ticks = 30 * 60;
  for (std::uint64_t n = 1; n <= ticks; ++n) {
    const AckWindow::time_point now = t0 + tick * static_cast<long>(n);
    // Every sixth tick (100 ms) the reader takes the oldest and acknowledges it.
    if (n % 6 == 0 && !unread.empty()) {
      const std::uint64_t taken = unread.front();
      unread.pop_front();
      window.acked(taken, now);
      if (n > ticks - 600) {
        run.worst_age_s = std::max(run.worst_age_s, static_cast<double>(n - taken) / 60.0);
      }
    }
    if (window.open()) {
      window.sent(n, now);
      unread.push_back(n);
    }
    run.largest_window = std::max(run.largest_window, window.window());
  }
  return run;
}

TEST(AckWindowSlowReader, AnAskedWindowHoldsTheDelayAtWindowOverTheReadRate) {
  AckWindow window(12, false, {std::chrono::nanoseconds(16'666'667), 64});
  const SlowReaderRun run = read_slowly(window);
  EXPECT_EQ(run.largest_window, 12u);
  EXPECT_LE(run.worst_age_s, 12 / 10.0 + 1 / 60.0);
}

TEST(AckWindowSlowReader, AnAdaptiveWindowGrowsToTheCapAndTheDelayStopsThere) {
  AckWindow window(12, true, {std::chrono::nanoseconds(16'666'667), 64});
  const SlowReaderRun run = read_slowly(window);
  EXPECT_EQ(run.largest_window, 64u);
  EXPECT_GT(run.worst_age_s, 12 / 10.0 + 1.0) << "the documented growth";
  EXPECT_LE(run.worst_age_s, 64 / 10.0 + 1 / 60.0);
}

}  // namespace
}  // namespace server
