// Bodies at rest come exactly to rest, and small rained piles fall asleep.
//
// Two mechanisms are checked here (docs/PHYSICS.md, "Resting contact"):
//   near misses: a pair left a slop apart by the push that separated it is still a
//     contact for the velocity pass. Without it a body whose support is not itself
//     supported (a ball wedged between two steep contacts) loses its contacts every
//     other step and "breathes": 0.15 m/s up and down, for ever;
//   held support: what a resting body's contacts held up last step is applied as a
//     force in the next, so it does not sink into its supports by g*dt^2/2 and get
//     pushed back out every step (in a pocket, that push comes out sideways and the
//     pile creeps).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "scenes/scenes.h"
#include "stability_scenes.h"

namespace phys::testing {
namespace {

// A ball wedged between two static balls whose contacts are 75 degrees from
// vertical (outside the 72.5 degrees that count as support). Bound: over the
// last 5 of 10 s no speed above 1e-9 m/s. Measured at 65 degrees, when support was
// 60: 1.4e-17; 0.15 m/s without either mechanism, 7e-7 m/s with near misses alone.
TEST(Resting, WedgedBallComesExactlyToRest) {
  WorldSettings settings;
  settings.sleeping = false;  // rest, not sleep, is what is measured
  World world(settings);
  const double angle = 75.0 * 3.14159265358979323846 / 180.0;
  for (const double side : {-1.0, 1.0}) {
    add_or_fail(world, circle_def({side * std::sin(angle), -std::cos(angle)}, 0.5, Motion::Static));
  }
  const BodyId ball = add_or_fail(world, circle_def({0.0, 0.0}, 0.5));
  double fastest = 0.0;
  for (int step = 1; step <= 600; ++step) {
    world.step(kDt);
    if (step > 300) fastest = std::max(fastest, length(world.body(ball)->velocity));
  }
  EXPECT_LT(fastest, 1e-9) << "m/s";
}

// Held support, measured where it acts: a ball resting in a pocket between two
// static balls whose contacts are 30 degrees from vertical (both support it).
// Without held support it sinks by g*dt^2/2 into both every step and is pushed back
// out along the two normals, which leaves it anywhere within about a slop (1e-5 m)
// of where it rested.
// Bound: from 0.5 s to 10.5 s it moves less than 1e-9 m. Measured: 1.2e-19 m with
// held support, 1.14e-5 m without (1.0e-5 to 1.4e-5 at 20 to 70 degrees).
double pocket_drift(bool hold) {
  WorldSettings settings;
  settings.sleeping = false;  // rest, not sleep, is what is measured
  settings.hold_resting_support = hold;
  World world(settings);
  const double angle = 30.0 * 3.14159265358979323846 / 180.0;
  for (const double side : {-1.0, 1.0}) {
    add_or_fail(world, circle_def({side * std::sin(angle), -std::cos(angle)}, 0.5, Motion::Static));
  }
  const BodyId ball = add_or_fail(world, circle_def({0.0, 0.0}, 0.5));
  for (int step = 0; step < 30; ++step) world.step(kDt);
  const Vec2 start = world.body(ball)->position;
  double drift = 0.0;
  for (int step = 0; step < 600; ++step) {
    world.step(kDt);
    drift = std::max(drift, length(world.body(ball)->position - start));
  }
  return drift;
}

constexpr double kMaxPocketDrift = 1e-9;  // m

TEST(Resting, BallInAPocketStaysWhereItRests) { EXPECT_LT(pocket_drift(true), kMaxPocketDrift); }

// The paired negative: without held support the same ball drifts beyond the bound.
TEST(RestingMechanism, WithoutHeldSupportTheBallInAPocketWanders) {
  EXPECT_GT(pocket_drift(false), kMaxPocketDrift);
}

struct SmallPile {
  double width;  // inner width of the container (m)
  int circles;
  double mu;
  double bound;         // seconds within which every circle must be asleep
  double measured;      // seconds it took at the last change (for the report)
  double without_hold;  // seconds it took without held support (0: not measured)
};

// `circles` circles of radius 0.5 rained in rows from 1 m up, 1.2 m apart, with a
// random jitter of 0.1 m and a random sideways speed of up to 1 m/s (the scene
// library's rained circles, which physics-settle builds too).
void build_small_pile(World& world, const SmallPile& pile) {
  scenes::add_to_world(world, scenes::rained_circles_scene({pile.width, pile.circles, pile.mu, 0}));
}

// The time from which every circle stays asleep to 40 s, or infinity when some
// circle is awake at 40 s.
double seconds_until_asleep(const SmallPile& pile, const WorldSettings& settings) {
  World world(settings);
  build_small_pile(world, pile);
  int asleep_at = -1;
  for (int step = 1; step <= 2400; ++step) {
    world.step(kDt);
    if (world.awake_body_count() == 0 && asleep_at < 0) asleep_at = step;
    if (world.awake_body_count() > 0) asleep_at = -1;
  }
  return asleep_at < 0 ? std::numeric_limits<double>::infinity() : asleep_at * kDt;
}

std::string small_pile_name(const SmallPile& p) {
  return "width" + std::to_string(static_cast<int>(p.width * 10.0)) + "dm_" +
         std::to_string(p.circles) + "_circles_mu" + std::to_string(static_cast<int>(p.mu * 10.0));
}

class SmallPiles : public ::testing::TestWithParam<SmallPile> {};

// Bound: every circle asleep within `bound` of the start, and still asleep at 40 s.
// Each bound lies between the time measured and the time without the mechanisms
// that made it (and, for the last three cases, the time without held support,
// checked by SmallPilesWithoutHeldSupport below).
// Measured before near misses and held support: 21.7 s, 13.1 s, 9.1 s, and never
// (within 40 s) for the three larger piles (in the order of the cases below).
// The last two cases (1,200 circles; 300 without friction) took 11.63 s and
// 16.90 s before piles fell asleep from the bottom up (docs/PHYSICS.md, "Sleep").
// The world has no setting for that; with it switched off in the current core (by
// hand, not committed) they took 8.03 s and never (still awake at 40 s),
// against 6.92 s and 10.18 s with it: hence bounds of 7.5 s and 13.5 s.
TEST_P(SmallPiles, FallAsleepAndStayAsleep) {
  const SmallPile pile = GetParam();
  const double seconds = seconds_until_asleep(pile, WorldSettings{});
  ASSERT_TRUE(std::isfinite(seconds)) << "still awake at 40 s";
  std::printf("%d circles, %.1f m, mu %.1f: asleep after %.2f s (measured %.2f s)\n", pile.circles,
              pile.width, pile.mu, seconds, pile.measured);
  EXPECT_LE(seconds, pile.bound);
}

INSTANTIATE_TEST_SUITE_P(Rained, SmallPiles,
                         ::testing::Values(SmallPile{3.6, 30, 0.5, 5.0, 1.63, 0.0},
                                           SmallPile{6.0, 30, 0.5, 5.0, 1.13, 0.0},
                                           SmallPile{10.0, 30, 0.5, 5.0, 1.12, 0.0},
                                           SmallPile{6.0, 100, 0.5, 10.0, 2.20, 0.0},
                                           SmallPile{10.0, 100, 0.5, 10.0, 1.60, 0.0},
                                           SmallPile{20.0, 300, 0.5, 5.0, 2.43, 8.98},
                                           SmallPile{20.0, 1200, 0.5, 7.5, 6.92, 16.88},
                                           SmallPile{20.0, 300, 0.0, 13.5, 10.18, 24.92}),
                         [](const auto& param_info) { return small_pile_name(param_info.param); });

class SmallPilesWithoutHeldSupport : public ::testing::TestWithParam<SmallPile> {};

// The paired negative of held support: with hold_resting_support off the same
// piles fall asleep only after their bounds (times in the cases' `without_hold`).
TEST_P(SmallPilesWithoutHeldSupport, FallAsleepOnlyAfterTheBound) {
  const SmallPile pile = GetParam();
  WorldSettings settings;
  settings.hold_resting_support = false;
  const double seconds = seconds_until_asleep(pile, settings);
  std::printf(
      "%d circles, %.1f m, mu %.1f, no held support: asleep after %.2f s (measured %.2f s)\n",
      pile.circles, pile.width, pile.mu, seconds, pile.without_hold);
  EXPECT_GT(seconds, pile.bound);
}

INSTANTIATE_TEST_SUITE_P(Rained, SmallPilesWithoutHeldSupport,
                         ::testing::Values(SmallPile{20.0, 300, 0.5, 5.0, 2.43, 8.98},
                                           SmallPile{20.0, 1200, 0.5, 7.5, 6.92, 16.88},
                                           SmallPile{20.0, 300, 0.0, 13.5, 10.18, 24.92}),
                         [](const auto& param_info) { return small_pile_name(param_info.param); });

struct DeepPile {
  double mu;
  double bound;     // the largest overlap allowed over the last 10 of 40 s (m)
  double measured;  // what it was at the last change (m)
};

// 2,000 circles rained into a container 20 m wide, a pile about 100 m deep: the
// overlap between any two circles (or a circle and the container), checked every
// second from 30 s to 40 s. Returns the largest, and the circles awake at 40 s.
struct DeepResult {
  double overlap;
  std::size_t awake;
};
DeepResult settle_deep_pile(double mu, const WorldSettings& settings) {
  World world(settings);
  build_small_pile(world, SmallPile{20.0, 2000, mu, 0.0, 0.0, 0.0});
  double worst = 0.0;
  for (int step = 1; step <= 2400; ++step) {
    world.step(kDt);
    if (step >= 1800 && step % 60 == 0) worst = std::max(worst, max_overlap(world.bodies()));
  }
  return {worst, world.awake_body_count()};
}

class DeepPiles : public ::testing::TestWithParam<DeepPile> {};

// Bounds: with friction 0.002 m; without, the 16,000-circle pile's 0.01 m, and every circle
// asleep at 40 s. Each guards a mechanism, measured with and without it (the
// mechanisms but held support have no setting: they were switched off by hand in
// the current core, not committed):
//   speculative contacts (a support a little below a body is a contact; without
//   them what rests above it falls freely onto it): at friction 0.5, 0.00016 m with
//   and 0.00353 m without; frictionless, asleep from 35.95 s with and 1,968 circles
//   awake at 40 s without (0.0049 and 0.0072 m: the overlap bound does not separate
//   them, the sleep check does; before the support cone of 72.5 degrees it was
//   0.119 m without). At 1, 2 and 5 they change nothing (0.0002, 0.00002, 0 m
//   without);
//   the squeeze rule (the position passes' static friction may not lower a body,
//   docs/PHYSICS.md, "Squeezes at high friction"): without it 0.0135, 0.036, 0.058
//   and 0.052 m at 0.5, 1, 2 and 5, against 0.00016, 0.00029, 0 and 0.00062 m with;
//   held support: at 0.5, 0.00332 m without (DeepPilesWithoutHeldSupport).
// With the support cone of 60 degrees (before 72.5) it measured 0.00089, 0.00412,
// 0.00284, 0.00014 and 0.00023 m in the order of the cases below.
// The samples are a second apart: sampled every 0.1 s the frictionless pile shows
// transient overlaps of up to 0.013 m between 30 and 40 s (avalanches), which the
// 0.01 m bound would not admit.
TEST_P(DeepPiles, KeepTheirOverlapWithinTheBound) {
  const DeepPile pile = GetParam();
  const DeepResult r = settle_deep_pile(pile.mu, WorldSettings{});
  std::printf("2000 circles, 20 m, mu %.1f: overlap %.3g m over 30-40 s (measured %.3g m)\n",
              pile.mu, r.overlap, pile.measured);
  EXPECT_LE(r.overlap, pile.bound);
  if (pile.mu == 0.0) {
    EXPECT_EQ(r.awake, 0u) << "circles awake at 40 s";
  }
}

INSTANTIATE_TEST_SUITE_P(Rained, DeepPiles,
                         ::testing::Values(DeepPile{0.5, 0.002, 0.00016},
                                           DeepPile{0.0, 0.01, 0.00485},
                                           DeepPile{1.0, 0.002, 0.00029}, DeepPile{2.0, 0.002, 0.0},
                                           DeepPile{5.0, 0.002, 0.00062}),
                         [](const auto& param_info) {
                           const double mu = param_info.param.mu;
                           if (mu == 0.0) return std::string("frictionless");
                           return mu == 0.5 ? std::string("mu_0_5")
                                            : "mu_" + std::to_string(static_cast<int>(mu));
                         });

// The paired negative of held support in the deep pile: at friction 0.5 its
// overlap goes beyond the bound of 0.002 m without it.
TEST(DeepPilesWithoutHeldSupport, OverlapBeyondTheBound) {
  WorldSettings settings;
  settings.hold_resting_support = false;
  const DeepResult r = settle_deep_pile(0.5, settings);
  std::printf("2000 circles, 20 m, mu 0.5, no held support: overlap %.3g m (measured 0.00332 m)\n",
              r.overlap);
  EXPECT_GT(r.overlap, 0.002);
}

}  // namespace
}  // namespace phys::testing
