// physics-client's game message schedule (client/game_message_plan.h), on a made-up
// clock: once by default, else a round every interval, late rounds not bunched; and
// the plans the server would refuse are refused before sending.
#include "client/game_message_plan.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

TEST(GameMessagePlan, WithoutAnIntervalOneRoundOnly) {
  client::GameMessageSender sender({{"jump"}, 0ms});
  const Clock::time_point t0{};
  EXPECT_TRUE(sender.take_round(t0));
  EXPECT_FALSE(sender.take_round(t0));
  EXPECT_FALSE(sender.take_round(t0 + 1h));
}

TEST(GameMessagePlan, EveryIntervalARoundAtTheFirstTickDueAfterIt) {
  client::GameMessageSender sender({{"dash"}, 100ms});
  const Clock::time_point t0{};
  int rounds = 0;
  // A tick every 16 ms for a second: a round at 0, then at the first tick at or
  // after each 100 ms step.
  for (int k = 0; k <= 62; ++k) rounds += sender.take_round(t0 + k * 16ms);
  EXPECT_EQ(rounds, 10);  // 0, 112, 208, 304, 400, 512, 608, 704, 800, 912
}

TEST(GameMessagePlan, ALateTickSendsOneRoundNotABurst) {
  client::GameMessageSender sender({{"dash"}, 10ms});
  const Clock::time_point t0{};
  EXPECT_TRUE(sender.take_round(t0));
  EXPECT_TRUE(sender.take_round(t0 + 1s));  // 99 rounds late: one round
  EXPECT_FALSE(sender.take_round(t0 + 1s + 9ms));
  EXPECT_TRUE(sender.take_round(t0 + 1s + 10ms));
}

TEST(GameMessagePlan, NoPayloadsNoRounds) {
  client::GameMessageSender sender({{}, 10ms});
  EXPECT_FALSE(sender.take_round(Clock::time_point{}));
}

TEST(GameMessagePlan, RefusesWhatTheServerWouldRefuse) {
  EXPECT_EQ(client::check_game_message_plan({{"jump", std::string(256, 'x')}, 0ms}), "");
  EXPECT_NE(client::check_game_message_plan({{std::string(257, 'x')}, 0ms}).find("257"),
            std::string::npos);
  EXPECT_NE(client::check_game_message_plan({{"a", "b", "c", "d", "e"}, 0ms}).find("at most 4"),
            std::string::npos);
  EXPECT_EQ(client::check_game_message_plan({{"a", "b", "c", "d"}, 0ms}), "");
  EXPECT_NE(client::check_game_message_plan({{"a"}, -1ms}), "");
}

}  // namespace
