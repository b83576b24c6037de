// The straggler policy: K consecutive timed-out ticks without input, then drop.
#include "stragglers.h"

#include <gtest/gtest.h>

namespace {

using server::ClientId;
using server::StragglerWatch;
using Ids = std::vector<ClientId>;

TEST(Stragglers, ReachedAfterKConsecutiveTimeoutsMissed) {
  StragglerWatch watch(3);
  EXPECT_TRUE(watch.after_step({7}, true).empty());
  EXPECT_TRUE(watch.after_step({7}, true).empty());
  EXPECT_EQ(watch.misses(7), 2);
  EXPECT_EQ(watch.after_step({7}, true), Ids{7});
}

TEST(Stragglers, AnInputInTimeStartsTheCountAfresh) {
  StragglerWatch watch(2);
  EXPECT_TRUE(watch.after_step({4}, true).empty());
  EXPECT_TRUE(watch.after_step({}, false).empty());  // 4 sent its input
  EXPECT_EQ(watch.misses(4), 0);
  EXPECT_TRUE(watch.after_step({4}, true).empty());
  EXPECT_EQ(watch.after_step({4, 2}, true), Ids{4});
  EXPECT_EQ(watch.misses(2), 1);
}

TEST(Stragglers, TicksWithoutTimeoutNeitherCountNorReset) {
  StragglerWatch watch(2);
  EXPECT_TRUE(watch.after_step({9}, true).empty());
  // 9 holds its input over, but the tick did not wait for it (e.g. it had sent a
  // later tick already): no miss counted, none forgiven.
  EXPECT_TRUE(watch.after_step({9}, false).empty());
  EXPECT_EQ(watch.misses(9), 1);
  EXPECT_EQ(watch.after_step({9}, true), Ids{9});
}

TEST(Stragglers, ZeroNeverDrops) {
  StragglerWatch watch(0);
  for (int i = 0; i < 100; ++i) EXPECT_TRUE(watch.after_step({1}, true).empty());
  EXPECT_EQ(watch.misses(1), 100);
}

}  // namespace
