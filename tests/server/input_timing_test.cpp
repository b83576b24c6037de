// How early inputs arrive, driven by hand (server/src/input_timing.h): the margin of
// each against its tick's due time, the least of them per client until taken, late
// inputs, and a lockstep server that sat idle.
#include "input_timing.h"

#include <gtest/gtest.h>

namespace server {
namespace {

using namespace std::chrono_literals;
using time_point = InputTiming::time_point;

const time_point kT0 = time_point{} + 100s;
constexpr std::chrono::nanoseconds kPeriod = 10ms;

TEST(InputTiming, MarginIsDueTimeLessArrival) {
  InputTiming timing(kPeriod, 250ms);
  timing.arrived(1, 5, kT0);
  timing.arrived(2, 5, kT0 + 7ms);
  timing.stepped(5, kT0 + 10ms);
  EXPECT_EQ(timing.take_least_margin(1), 10ms);
  EXPECT_EQ(timing.take_least_margin(2), 3ms);
  // Taken: nothing until the next input is measured.
  EXPECT_EQ(timing.take_least_margin(1), std::nullopt);
}

TEST(InputTiming, LeastMarginOverTheTicksUntilTaken) {
  InputTiming timing(kPeriod, 250ms);
  timing.arrived(1, 1, kT0);
  timing.arrived(1, 2, kT0 + 15ms);
  timing.stepped(1, kT0 + 10ms);  // 10 ms early
  timing.stepped(2, kT0 + 20ms);  // 5 ms early
  EXPECT_EQ(timing.take_least_margin(1), 5ms);
}

TEST(InputTiming, LockstepWaitingForAnInputReportsItLate) {
  // Realtime pace: tick 3 was due at 30 ms; the input came at 42 ms, and the tick
  // was stepped then. Its margin is -12 ms, not 0.
  InputTiming timing(kPeriod, 250ms);
  timing.arrived(1, 3, kT0 + 42ms);
  timing.stepped(3, kT0 + 30ms);
  EXPECT_EQ(timing.take_least_margin(1), -12ms);
}

TEST(InputTiming, InputForATickAlreadySteppedIsLateByItsTicksDueTime) {
  InputTiming timing(kPeriod, 250ms);
  timing.stepped(9, kT0 + 90ms);
  // Tick 8 was due a period before tick 9: at 80 ms. Arriving at 95 ms: -15 ms.
  timing.arrived(1, 8, kT0 + 95ms);
  EXPECT_EQ(timing.take_least_margin(1), -15ms);
}

TEST(InputTiming, IdleServerCountsTheFirstInputsArrivalAsDue) {
  InputTiming timing(kPeriod, 250ms);
  // No schedule yet (a lockstep run's first tick): due when the first input came.
  timing.arrived(1, 1, kT0 + 3ms);
  timing.arrived(2, 1, kT0 + 8ms);
  EXPECT_EQ(timing.stepped(1, std::nullopt), kT0 + 3ms);
  EXPECT_EQ(timing.take_least_margin(1), 0ms);
  EXPECT_EQ(timing.take_least_margin(2), -5ms);
  // Scheduled long before anyone sent (the server sat idle a second): the same.
  timing.arrived(1, 2, kT0 + 2s);
  EXPECT_EQ(timing.stepped(2, kT0 + 20ms), kT0 + 2s);
  EXPECT_EQ(timing.take_least_margin(1), 0ms);
}

TEST(InputTiming, ForgottenClientsAndSteppedTicksHoldNothing) {
  InputTiming timing(kPeriod, 250ms);
  for (std::uint64_t t = 1; t <= 100; ++t) timing.arrived(1, t, kT0);
  timing.forget(1);
  timing.stepped(1, kT0);
  EXPECT_EQ(timing.take_least_margin(1), std::nullopt);
}

}  // namespace
}  // namespace server
