// Outcome and Expected under GoogleTest: a failure's message is what GoogleTest
// prints, without physics::testing linking GoogleTest.
#include "physics_testing/outcome.h"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace physics_testing {
namespace {

static_assert(std::is_convertible_v<Outcome, ::testing::AssertionResult>);
static_assert(std::is_convertible_v<Expected<int>, ::testing::AssertionResult>);
static_assert(!std::is_convertible_v<Outcome, bool>, "explicit, so it never turns into an int");

Outcome failing() { return Outcome::failure("tick 7: hash 0x1 differs from 0x2"); }

TEST(Outcome, AFailureBecomesAFalseAssertionResultWithItsMessage) {
  const ::testing::AssertionResult result = failing();
  EXPECT_FALSE(static_cast<bool>(result));
  EXPECT_STREQ(result.message(), "tick 7: hash 0x1 differs from 0x2");
  const ::testing::AssertionResult good = Outcome::success();
  EXPECT_TRUE(static_cast<bool>(good));
}

TEST(Outcome, ExpectTruePrintsTheMessageOfAFailure) {
  EXPECT_NONFATAL_FAILURE(EXPECT_TRUE(failing()), "tick 7: hash 0x1 differs from 0x2");
}

TEST(Outcome, PrintsWithItsVerdict) {
  std::ostringstream out;
  out << failing() << " | " << Outcome::success();
  EXPECT_EQ(out.str(), "failed: tick 7: hash 0x1 differs from 0x2 | ok");
}

TEST(Expected, HoldsTheValueOrTheMessage) {
  Expected<int> good = 42;
  ASSERT_TRUE(good);
  EXPECT_EQ(*good, 42);
  EXPECT_TRUE(good.outcome().ok());

  Expected<int> bad = Expected<int>::failure("no snapshot within 100 ms");
  EXPECT_FALSE(bad);
  EXPECT_EQ(bad.message(), "no snapshot within 100 ms");
  EXPECT_THROW((void)bad.value(), std::logic_error);
  EXPECT_NONFATAL_FAILURE(EXPECT_TRUE(bad), "no snapshot within 100 ms");
}

}  // namespace
}  // namespace physics_testing
