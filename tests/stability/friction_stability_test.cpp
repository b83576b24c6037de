// Velocity decay at any dt*k. Bound: for dt*k in {0.5, 1, 2, 10, 100}, with every
// integrator, a sliding body's velocity never changes sign and never grows, on
// any step. Its error against the exact decay v0*exp(-k t) is reported (as a test
// property and on stdout); for the integrators whose friction is the exact decay
// (SemiImplicitEuler and Exact, settings.h) it is also bounded by rounding:
// 1e-12 relative over 120 steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include "stability_scenes.h"

namespace phys::testing {
namespace {

constexpr double kV0 = 10.0;
constexpr int kSteps = 120;

class FrictionDecay : public ::testing::TestWithParam<std::tuple<Integrator, double>> {
 protected:
  Integrator integrator() const { return std::get<0>(GetParam()); }
  double dt_k() const { return std::get<1>(GetParam()); }
  double rate() const { return dt_k() / kDt; }
};

TEST_P(FrictionDecay, NeverChangesSignNorGrowsAndTracksTheExactDecay) {
  WorldSettings settings = zero_gravity();
  settings.integrator = integrator();
  settings.sleeping = false;  // measure friction alone, not the sleep threshold
  World world(settings);
  BodyDef def = box_def({0.0, 0.0}, {0.5, 0.5});
  def.velocity = {kV0, -kV0};
  def.friction = {rate(), rate()};
  const BodyId id = add_or_fail(world, def);

  Vec2 previous = def.velocity;
  double previous_x = 0.0;
  double worst_relative_error = 0.0;
  for (int step = 1; step <= kSteps; ++step) {
    world.step(kDt);
    const BodyState s = *world.body(id);
    ASSERT_GE(s.velocity.x, 0.0) << "sign changed at step " << step;
    ASSERT_LE(s.velocity.x, previous.x) << "grew at step " << step;
    ASSERT_LE(s.velocity.y, 0.0) << "sign changed at step " << step;
    ASSERT_GE(s.velocity.y, previous.y) << "grew at step " << step;
    ASSERT_GE(s.position.x, previous_x) << "moved backwards at step " << step;
    const double exact = kV0 * std::exp(-rate() * step * kDt);
    // Relative error is measured while v stays a normal double (> 1e-290);
    // below that, subnormal rounding is absolute, not relative.
    if (exact > 1.0e-290) {
      worst_relative_error = std::max(worst_relative_error, std::abs(s.velocity.x - exact) / exact);
    }
    previous = s.velocity;
    previous_x = s.position.x;
  }
  RecordProperty("worst_relative_error", std::to_string(worst_relative_error));
  std::printf("friction %-18s dt*k=%-5g worst relative error vs v0*exp(-kt): %.3g\n",
              to_string(integrator()), dt_k(), worst_relative_error);
  if (integrator() != Integrator::ExplicitEuler) {
    EXPECT_LE(worst_relative_error, 1.0e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(DtTimesK, FrictionDecay,
                         ::testing::Combine(::testing::Values(Integrator::ExplicitEuler,
                                                              Integrator::SemiImplicitEuler,
                                                              Integrator::Exact),
                                            ::testing::Values(0.5, 1.0, 2.0, 10.0, 100.0)),
                         [](const auto& case_info) {
                           return test_name(std::string(to_string(std::get<0>(case_info.param))) +
                                            "_dtk_" + std::to_string(std::get<1>(case_info.param)));
                         });

// The Exact integrator also moves the body the exact distance v0 (1 - e^{-kt}) / k.
class ExactFrictionDistance : public ::testing::TestWithParam<double> {
 protected:
  double rate() const { return GetParam() / kDt; }
};

TEST_P(ExactFrictionDistance, IsTheClosedForm) {
  WorldSettings settings = zero_gravity();
  settings.sleeping = false;
  World world(settings);
  BodyDef def = box_def({0.0, 0.0}, {0.5, 0.5});
  def.velocity = {kV0, 0.0};
  def.friction = {rate(), 0.0};
  const BodyId id = add_or_fail(world, def);
  for (int step = 0; step < kSteps; ++step) world.step(kDt);
  // x(t) = v0 (1 - e^{-kt}) / k
  const double t = kSteps * kDt;
  const double expected = kV0 * (1.0 - std::exp(-rate() * t)) / rate();
  EXPECT_NEAR(world.body(id)->position.x, expected, 1.0e-12 * expected);
}

INSTANTIATE_TEST_SUITE_P(DtTimesK, ExactFrictionDistance,
                         ::testing::Values(0.5, 1.0, 2.0, 10.0, 100.0));

}  // namespace
}  // namespace phys::testing
