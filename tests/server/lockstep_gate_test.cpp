// The lockstep gate, with time passed in by hand.
#include "server/lockstep_gate.h"

#include <gtest/gtest.h>

namespace {

using server::LockstepGate;
using namespace std::chrono_literals;
using Decision = LockstepGate::Decision;

const LockstepGate::time_point t0{};

TEST(LockstepGate, WaitsWithoutDeadlineWhenNobodySentAnything) {
  LockstepGate gate(250ms);
  EXPECT_EQ(gate.decide(false, false, t0), Decision::Wait);
  EXPECT_EQ(gate.decide(false, false, t0 + 10s), Decision::Wait);
  EXPECT_FALSE(gate.deadline().has_value());
}

TEST(LockstepGate, StepsAsSoonAsEveryInputIsThere) {
  LockstepGate gate(250ms);
  EXPECT_EQ(gate.decide(true, true, t0), Decision::Step);
}

TEST(LockstepGate, TimeoutCountsFromTheFirstInputForTheTick) {
  LockstepGate gate(250ms);
  EXPECT_EQ(gate.decide(false, true, t0 + 1s), Decision::Wait);
  ASSERT_TRUE(gate.deadline().has_value());
  EXPECT_EQ(*gate.deadline(), t0 + 1s + 250ms);
  EXPECT_EQ(gate.decide(false, true, t0 + 1s + 249ms), Decision::Wait);
  EXPECT_EQ(gate.decide(false, true, t0 + 1s + 250ms), Decision::StepAfterTimeout);
}

TEST(LockstepGate, AfterAStepTheWaitStartsAgain) {
  LockstepGate gate(250ms);
  EXPECT_EQ(gate.decide(false, true, t0), Decision::Wait);
  EXPECT_EQ(gate.decide(false, true, t0 + 300ms), Decision::StepAfterTimeout);
  gate.stepped();
  EXPECT_EQ(gate.decide(false, true, t0 + 300ms), Decision::Wait);
  EXPECT_EQ(gate.decide(false, true, t0 + 549ms), Decision::Wait);
  EXPECT_EQ(gate.decide(false, true, t0 + 550ms), Decision::StepAfterTimeout);
}

TEST(LockstepGate, MissingInputArrivingInTimeStepsWithoutTimeout) {
  LockstepGate gate(250ms);
  EXPECT_EQ(gate.decide(false, true, t0), Decision::Wait);
  EXPECT_EQ(gate.decide(true, true, t0 + 100ms), Decision::Step);
}

TEST(LockstepGate, WaitIsForgottenWhenTheWaitingInputsGoAway) {
  // The only client that had sent an input left: nothing is waiting any more.
  LockstepGate gate(250ms);
  EXPECT_EQ(gate.decide(false, true, t0), Decision::Wait);
  EXPECT_EQ(gate.decide(false, false, t0 + 100ms), Decision::Wait);
  EXPECT_FALSE(gate.deadline().has_value());
}

}  // namespace
