// The window of unacknowledged snapshots (server/src/ack_window.h): fixed when the
// client asked for one, grown with the round trip when it did not, never past the cap.
#include "ack_window.h"

#include <gtest/gtest.h>

namespace server {
namespace {

using namespace std::chrono_literals;
using time_point = AckWindow::time_point;

const time_point kT0 = time_point{} + 100s;
const AckWindow::Sizing kSixtyHertz{std::chrono::nanoseconds(16'666'667), 64};

// Sends `count` snapshots one period apart from `first`, each acknowledged
// `round_trip` after it was sent.
void run(AckWindow& window, std::uint64_t first, int count, std::chrono::nanoseconds round_trip) {
  for (int i = 0; i < count; ++i) {
    const std::uint64_t tick = first + static_cast<std::uint64_t>(i);
    const time_point at = kT0 + kSixtyHertz.snapshot_period * static_cast<int>(tick);
    window.sent(tick, at);
    window.acked(tick, at + round_trip);
  }
}

TEST(AckWindow, AdaptiveWindowCoversTheRoundTrip) {
  AckWindow window(12, true, kSixtyHertz);
  EXPECT_EQ(window.window(), 12u);  // no round trip measured yet
  run(window, 1, 10, 200ms);
  // 200 ms is 12 snapshots; a quarter more and four: ceil(15) + 4.
  EXPECT_EQ(window.round_trip(), 200ms);
  EXPECT_EQ(window.window(), 19u);
  // A short path keeps the floor.
  AckWindow near(12, true, kSixtyHertz);
  run(near, 1, 10, 1ms);
  EXPECT_EQ(near.window(), 12u);
}

TEST(AckWindow, RoundTripIsTheLeastOfTheLastTwoSeconds) {
  AckWindow window(12, true, kSixtyHertz);
  run(window, 1, 10, 300ms);
  run(window, 11, 5, 200ms);
  EXPECT_EQ(window.round_trip(), 200ms);
  // Three seconds later the path is long again: the short samples have aged out.
  run(window, 300, 10, 300ms);
  EXPECT_EQ(window.round_trip(), 300ms);
}

TEST(AckWindow, CappedAtTheServersLargest) {
  AckWindow window(12, true, kSixtyHertz);
  run(window, 1, 10, 5s);
  EXPECT_EQ(window.window(), 64u);
}

TEST(AckWindow, AskedForWindowNeverGrows) {
  AckWindow window(12, false, kSixtyHertz);
  run(window, 1, 10, 400ms);
  EXPECT_EQ(window.window(), 12u);
}

TEST(AckWindow, OpenUntilTheWindowIsOutstanding) {
  AckWindow window(3, false, kSixtyHertz);
  window.sent(1, kT0);
  window.sent(2, kT0);
  EXPECT_TRUE(window.open());
  window.sent(3, kT0);
  EXPECT_FALSE(window.open());
  window.acked(2, kT0 + 1ms);  // frees 1 and 2
  EXPECT_EQ(window.unacknowledged(), 1u);
  EXPECT_TRUE(window.open());
}

}  // namespace
}  // namespace server
