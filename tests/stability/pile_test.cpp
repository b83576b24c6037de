// The 16,000-circle pile: 16,000 circles of radius 0.5 rained into a container
// 100 m wide with walls 500 m high, from up to 240 m, each with a random sideways
// speed of up to 1 m/s so that they tumble into a pile rather than land as columns.
// Bounds:
//   none escapes (every centre stays inside the container), checked every 10 steps;
//   nothing becomes NaN or infinite, checked every 10 steps;
//   after settling (30 s with contact friction, 75 s without), every circle is
//   asleep, and no two circles (nor a circle and the container) overlap by more
//   than 0.003 m with contact friction, 0.01 m (the 16,000-circle pile's bound) without;
//   once asleep, the pile stays asleep for 10 s more: no circle wakes, none moves
//   (positions equal to the bit), and the kinetic energy is exactly 0.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "scenes/scenes.h"
#include "stability_scenes.h"

namespace phys::testing {
namespace {

constexpr int kCircles = 16'000;
constexpr double kInner = 50.0;  // inner faces of the walls at x = +-50
constexpr double kWallTop = 500.0;
constexpr int kSettleSteps = 1800;  // 30 s
constexpr int kWatchSteps = 600;    // 10 s more
// The overlap bounds, each between the figure measured and the figure without the
// mechanism it guards (see the two tests below).
constexpr double kMaxOverlapWithFriction = 0.003;
constexpr double kMaxOverlapFrictionless = 0.01;

// The container and the circles, all with contact friction `mu` (the scene
// library's circle pile, which the bench's pile-rain scenes and physics-settle share).
void build_pile(World& world, double mu) {
  scenes::add_to_world(world, scenes::rained_circles_scene(scenes::circle_pile(kCircles, mu)));
}

void expect_contained(const std::vector<BodyState>& bodies, int step) {
  ASSERT_TRUE(all_finite(bodies)) << "non-finite state at step " << step;
  for (const BodyState& b : bodies) {
    if (b.motion == Motion::Static) continue;
    ASSERT_GT(b.position.x, -kInner) << "escaped left at step " << step;
    ASSERT_LT(b.position.x, kInner) << "escaped right at step " << step;
    ASSERT_GT(b.position.y, 0.0) << "fell through the floor at step " << step;
    ASSERT_LT(b.position.y, kWallTop) << "flew out at step " << step;
  }
}

// Rains the pile with contact friction `mu`, lets it settle for 30 s, then watches
// it for 10 s more (the bounds in the file's header).
class SettlingPile : public ::testing::Test {
 protected:
  void settle(double mu, double max_overlap_bound, int settle_steps = kSettleSteps) {
    World world;
    build_pile(world, mu);
    ASSERT_EQ(world.dynamic_body_count(), static_cast<std::size_t>(kCircles));
    const auto began = std::chrono::steady_clock::now();
    for (int step = 1; step <= settle_steps; ++step) {
      world.step(kDt);
      if (step % 10 == 0) {
        ASSERT_NO_FATAL_FAILURE(expect_contained(world.bodies(), step));
      }
    }
    const double settle_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    std::vector<BodyState> bodies = world.bodies();
    const double settled_overlap = max_overlap(bodies);
    const double energy = kinetic_energy(bodies);
    std::printf(
        "pile: settled after %d steps in %.1f s wall; overlap %.4g m, KE %.4g J, awake %zu\n",
        settle_steps, settle_seconds, settled_overlap, energy, world.awake_body_count());
    EXPECT_LE(settled_overlap, max_overlap_bound);
    ASSERT_EQ(world.awake_body_count(), 0U)
        << "circles still awake after " << settle_steps / 60 << " s";

    // Asleep, the pile must stay as it is: nothing wakes it, nothing nudges it.
    const std::vector<BodyState> settled = bodies;
    for (int step = 1; step <= kWatchSteps; ++step) {
      world.step(kDt);
      ASSERT_EQ(world.awake_body_count(), 0U) << "woke at step " << settle_steps + step;
      if (step % 10 == 0 || step == kWatchSteps) {
        bodies = world.bodies();
        ASSERT_EQ(bodies.size(), settled.size());
        for (std::size_t i = 0; i < bodies.size(); ++i) {
          ASSERT_EQ(bodies[i].position, settled[i].position)
              << "body " << i << " moved asleep by step " << settle_steps + step;
        }
        ASSERT_EQ(kinetic_energy(bodies), 0.0) << "at step " << settle_steps + step;
      }
    }
  }
};

// Settling, with friction: by 30 s every circle is asleep (piles fall asleep from the
// bottom up, docs/PHYSICS.md, "Sleep"), the overlap is within the bound, and for
// 10 s more it stays asleep and unmoved. The stability test's friction is 0.5;
// the pile's specification names none, so 1, 2 and 5 are checked too.
// Measured (Release, current core): KE 0 at every friction; settled overlap
// 0.0010, 0.0004, 0.0002 and 0.0002 m at 0.5, 1, 2 and 5 (frozen when the pair
// falls asleep; 0.0010, 0.0014, 0.0021 and 0.0007 m with the support cone of 60
// degrees). The bound, 0.003 m, guards the squeeze rule: before the position
// passes' static friction stopped lowering bodies (docs/PHYSICS.md, "Squeezes at
// high friction") it was 0.0077 m at 0.5, and 0.029 m at 1: a circle squeezed
// against the wall by a neighbour, whose escape up the wall the wall's static
// friction undid in every pass. The world has no setting for the rule; with it
// switched off by hand in the current core (not committed) the settled overlap is
// 0.039, 0.063, 0.023 and 0.034 m at 0.5, 1, 2 and 5, and every case fails.
class SettlingWithFriction : public SettlingPile, public ::testing::WithParamInterface<double> {};

TEST_P(SettlingWithFriction, FallsAsleepWithoutOverlapAndStaysAsleep) {
  settle(GetParam(), kMaxOverlapWithFriction);
}

INSTANTIATE_TEST_SUITE_P(ContactFriction, SettlingWithFriction,
                         ::testing::Values(0.5, 1.0, 2.0, 5.0), [](const auto& param_info) {
                           const double mu = param_info.param;
                           return mu == 0.5 ? std::string("mu_0_5")
                                            : "mu_" + std::to_string(static_cast<int>(mu));
                         });

// Frictionless, the pile flows like a liquid for longer: the equal circles pack in
// a hexagonal lattice, and the holes left in it rise like bubbles (the circle above a
// hole falls into it, leaving a hole above itself). So it settles for 75 s, not 30.
// Measured (Release, current core; build/bench/physics-settle --width 100 --circles
// 16000 --per-row 80 --mu 0 --seconds 75 is this pile): 6,419 circles awake at 30 s,
// all asleep from 43.5 s, overlap 0.0042 m, KE 0. With the support cone of 60 degrees
// (docs/PHYSICS.md, "Stacks: shock propagation") it fell asleep only at 60 s, with
// 0.0148 m frozen in rows of side-by-side circles compressed end to end, and this
// test was disabled: the bound of 0.01 m lies between 0.0042 and 0.0148 m (the cone
// is a constant of the core, with no setting).
constexpr int kFrictionlessSettleSteps = 4500;  // 75 s

TEST_F(SettlingPile, FrictionlessFallsAsleepWithoutOverlapAndStaysAsleep) {
  settle(0.0, kMaxOverlapFrictionless, kFrictionlessSettleSteps);
}

}  // namespace
}  // namespace phys::testing
