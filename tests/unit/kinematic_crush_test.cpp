// A dynamic body caught between a moving kinematic body and a static one is
// crushed: the static body wins, the dynamic body stays on its near side and may
// overlap the kinematic one, and World::crush_events reports the three bodies on
// every step it is pinned, and on no other. The sweeper's case: a player (a circle,
// then a box) on a floor, swept against a static wall by a kinematic wall that goes
// on until the gap is a fifth of the player, stops, and goes back, at several speeds and tick
// rates.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

// The static wall's near face, and the player's size (a circle's radius, a box's
// half width and height).
constexpr double kWallFace = 4.75;
constexpr double kPlayerHalf = 0.5;
constexpr double kSweeperHalfWidth = 0.5;
// Where the sweeper's front face stops: 0.2 m from the wall, the player 0.8 m deep
// in it (less than the width of either, so that it still pushes toward the wall).
constexpr double kSweepEnd = kWallFace - 0.2;
// How far the player may sink into the static wall at the end of a step: the
// slop the position passes leave, with room for rounding.
constexpr double kSinkBound = 1.0e-4;

struct SweepCase {
  Shape player;
  double speed;  // the sweeper's, m/s
  int hz;
};

std::string case_name(const ::testing::TestParamInfo<SweepCase>& info) {
  const SweepCase& c = info.param;
  return test_name(std::string(c.player == Shape::Circle ? "circle" : "box") + "_" +
                   std::to_string(static_cast<int>(c.speed * 10)) + "dm_per_s_" +
                   std::to_string(c.hz) + "hz");
}

class KinematicCrush : public ::testing::TestWithParam<SweepCase> {
 protected:
  void SetUp() override {
    world_.set_contact_events(false);
    add_or_fail(world_, box_def({0.0, -0.5}, {20.0, 0.5}, Motion::Static));  // floor, top y = 0
    wall_ = add_or_fail(world_, box_def({kWallFace + 0.25, 1.5}, {0.25, 1.5}, Motion::Static));
    sweeper_ =
        add_or_fail(world_, box_def({1.0, 1.5}, {kSweeperHalfWidth, 1.5}, Motion::Kinematic));
    const Vec2 at{3.0, kPlayerHalf};
    player_ = add_or_fail(world_, GetParam().player == Shape::Circle
                                      ? circle_def(at, kPlayerHalf)
                                      : box_def(at, {kPlayerHalf, kPlayerHalf}));
  }

  double sweeper_front() const { return world_.body(sweeper_)->position.x + kSweeperHalfWidth; }

  // Whether the last step reported the player crushed by the sweeper against the wall.
  bool crushed() const {
    const auto& events = world_.crush_events();
    return std::any_of(events.begin(), events.end(), [&](const CrushEvent& e) {
      return e.step == world_.step_count() && e.kinematic == sweeper_ && e.dynamic == player_ &&
             e.fixed == wall_;
    });
  }

  // One step with the sweeper at `velocity`, then the checks on the player: never
  // past the wall, never sunk into it beyond the bound, and crushed exactly while
  // the gap between the sweeper and the wall is narrower than the player (a step's
  // motion either side of the moment it closes is left to the solver).
  void step_and_check(double velocity, double dt) {
    ASSERT_TRUE(world_.set_velocity(sweeper_, {velocity, 0.0}));
    world_.step(dt);
    const BodyState player = *world_.body(player_);
    const double sunk = player.position.x + kPlayerHalf - kWallFace;
    worst_sink_ = std::max(worst_sink_, sunk);
    ASSERT_LT(player.position.x, kWallFace) << "step " << world_.step_count();
    ASSERT_LT(sunk, kSinkBound) << "step " << world_.step_count();
    const double gap = kWallFace - sweeper_front();
    const double edge = std::abs(gap - 2.0 * kPlayerHalf);
    if (edge > GetParam().speed * dt + 0.01) {
      ASSERT_EQ(crushed(), gap < 2.0 * kPlayerHalf)
          << "step " << world_.step_count() << ", gap " << gap;
    }
    pinned_steps_ += crushed() ? 1 : 0;
  }

  World world_{WorldSettings{}};
  BodyId wall_;
  BodyId sweeper_;
  BodyId player_;
  double worst_sink_ = -1.0;
  int pinned_steps_ = 0;
};

TEST_P(KinematicCrush, ThePlayerStaysOnTheNearSideAndIsReportedCrushedWhilePinned) {
  const SweepCase c = GetParam();
  const double dt = 1.0 / c.hz;
  for (int n = 0; n < c.hz / 2; ++n) {  // the player settles
    ASSERT_NO_FATAL_FAILURE(step_and_check(0.0, dt));
  }
  // In: until the sweeper's front is at the sweep's end (the last step shorter).
  while (sweeper_front() < kSweepEnd - 1e-9) {
    ASSERT_NO_FATAL_FAILURE(
        step_and_check(std::min(c.speed, (kSweepEnd - sweeper_front()) / dt), dt));
  }
  ASSERT_TRUE(crushed());
  // Held still, pinned, for twice the sleep time: a pinned body stays awake.
  for (int n = 0; n < c.hz; ++n) {
    ASSERT_NO_FATAL_FAILURE(step_and_check(0.0, dt));
  }
  ASSERT_TRUE(crushed());
  // Out again, until the sweeper is well clear of the player.
  while (sweeper_front() > 2.5) {
    ASSERT_NO_FATAL_FAILURE(step_and_check(-c.speed, dt));
  }
  EXPECT_FALSE(crushed());
  EXPECT_GT(pinned_steps_, c.hz);
  // The player ends against the wall, on its near side.
  const BodyState player = *world_.body(player_);
  EXPECT_NEAR(player.position.x, kWallFace - kPlayerHalf, 0.01);
  EXPECT_LT(worst_sink_, kSinkBound);
}

// Speeds up to 20 m/s: 0.67 m in a 30 Hz step, two thirds of the player's width.
// What limits it is that a kinematic body is not swept against dynamic ones: it
// jumps its velocity times the sub-step, and a jump near the player's width or more
// may land beyond the player (at 30 m/s and 30 Hz it passed over it) or throw it
// (at 45 m/s and 60 Hz, through the wall).
std::vector<SweepCase> sweep_cases() {
  std::vector<SweepCase> cases;
  for (const Shape shape : {Shape::Circle, Shape::Box}) {
    for (const double speed : {0.5, 2.0, 5.0, 10.0, 20.0}) {
      for (const int hz : {30, 60, 120}) cases.push_back({shape, speed, hz});
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Sweeps, KinematicCrush, ::testing::ValuesIn(sweep_cases()), case_name);

}  // namespace
}  // namespace phys::testing
