// Contact events (physics/contact_events.h): a dropped ball's first contact at the
// step and speed the integrator gives by hand, begins and ends of a bouncing ball,
// a resting pair that sleeps and the end a removal brings, determinism, and events
// off costing no stage any work and changing no state.
#include "physics/contact_events.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "physics_test_support.h"
#include "scenes/random.h"

namespace phys::testing {
namespace {

using scenes::Rain;

constexpr double kG = 9.81;
// A ball of radius 0.5 whose centre starts 5 m above the level at which it touches
// a floor whose top is y = 0 (the centre at y = 0.5).
constexpr double kRadius = 0.5;
constexpr double kDrop = 5.0;

// The Exact integrator follows free fall to rounding: the centre is at
// 0.5 + kDrop - g t^2 / 2, so the ball reaches the floor at T = sqrt(2 H / g), in
// the step n with (n - 1) dt < T <= n dt, and closes at g T = sqrt(2 g H). The swept
// move stops it at that time of impact (bisection to the last bit of t), so the
// speed is the impact's, not the end of the step's: the bound below is far under the
// g dt = 0.16 m/s a speed taken at a step's end would be off by, and far over the
// rounding of 61 steps of a 10 m/s fall (about 1e-13).
constexpr double kSpeedBound = 1.0e-9;
double impact_time() { return std::sqrt(2.0 * kDrop / kG); }
std::uint64_t step_containing(double t) { return static_cast<std::uint64_t>(std::ceil(t / kDt)); }

class ContactEvents : public WorldTest {
 protected:
  // The floor first (index 0), the ball second: events name the floor as `a`.
  BodyId drop_ball(double restitution) {
    floor_ = make_floor(0.0);
    BodyDef def = circle_def({0.0, kRadius + kDrop}, kRadius);
    def.restitution = restitution;
    return add(def);
  }
  // Steps n times, gathering every event.
  void run(int n) {
    for (int i = 0; i < n; ++i) {
      world_.step(kDt);
      const auto& events = world_.contact_events();
      seen_.insert(seen_.end(), events.begin(), events.end());
    }
  }

  BodyId floor_;
  std::vector<ContactEvent> seen_;
};

TEST_F(ContactEvents, ADroppedBallBeginsAtTheStepAndSpeedOfItsFreeFall) {
  const BodyId ball = drop_ball(0.0);
  world_.set_contact_events(true);
  run(240);                                        // 4 s: it lands, rests and falls asleep
  ASSERT_EQ(step_containing(impact_time()), 61u);  // T = 1.0096 s, 60.58 steps
  ASSERT_EQ(seen_.size(), 1u) << "a ball at rest and then asleep keeps its one contact";
  const ContactEvent& e = seen_[0];
  EXPECT_EQ(e.kind, ContactEventKind::Begin);
  EXPECT_EQ(e.step, 61u);
  EXPECT_EQ(e.a, floor_);
  EXPECT_EQ(e.b, ball);
  EXPECT_NEAR(e.closing_speed, std::sqrt(2.0 * kG * kDrop), kSpeedBound);
  EXPECT_EQ(e.normal, (Vec2{0.0, 1.0}));  // from the floor toward the ball
  EXPECT_NEAR(e.point.x, 0.0, 1.0e-12);
  EXPECT_NEAR(e.point.y, 0.0, 1.0e-9);  // where the surfaces meet
  EXPECT_FALSE(state(ball).awake);
  EXPECT_EQ(world_.contacts_in_touch(), 1u);
  EXPECT_EQ(world_.counters().contact_events, 1u);
}

TEST_F(ContactEvents, ABouncingBallBeginsAndEndsEachBounce) {
  const double e = 0.5;
  const BodyId ball = drop_ball(e);
  world_.set_contact_events(true);
  run(600);
  const double t1 = impact_time();
  const double v1 = std::sqrt(2.0 * kG * kDrop);
  // Bounced at e * v1, it leaves the floor within the step of impact and is apart
  // after the next; it is back at the level after 2 e v1 / g = 2 e T, at 2 T.
  const double t2 = t1 + 2.0 * e * v1 / kG;
  ASSERT_GE(seen_.size(), 4u);
  EXPECT_EQ(seen_[0].kind, ContactEventKind::Begin);
  EXPECT_EQ(seen_[0].step, step_containing(t1));
  EXPECT_NEAR(seen_[0].closing_speed, v1, kSpeedBound);
  EXPECT_EQ(seen_[1].kind, ContactEventKind::End);
  EXPECT_EQ(seen_[1].step, step_containing(t1) + 1);
  // After the step it ended in, rising at e v1 less what gravity took since T.
  const double t_end = static_cast<double>(seen_[1].step) * kDt;
  EXPECT_NEAR(seen_[1].closing_speed, -(e * v1 - kG * (t_end - t1)), kSpeedBound);
  EXPECT_EQ(seen_[1].normal, (Vec2{0.0, 1.0}));
  EXPECT_EQ(seen_[2].kind, ContactEventKind::Begin);
  EXPECT_EQ(seen_[2].step, step_containing(t2));
  EXPECT_NEAR(seen_[2].closing_speed, e * v1, kSpeedBound);
  EXPECT_EQ(seen_[3].kind, ContactEventKind::End);
  EXPECT_EQ(seen_[3].step, step_containing(t2) + 1);
  // Begins and ends alternate; bounces slower than the rest speed stay, so the
  // last is a begin, and the ball sleeps on it.
  for (std::size_t i = 0; i < seen_.size(); ++i) {
    EXPECT_EQ(seen_[i].kind, i % 2 == 0 ? ContactEventKind::Begin : ContactEventKind::End) << i;
    EXPECT_EQ(seen_[i].b, ball);
    if (i > 0) {
      EXPECT_GT(seen_[i].step, seen_[i - 1].step);
    }
  }
  EXPECT_EQ(seen_.back().kind, ContactEventKind::Begin);
  EXPECT_FALSE(state(ball).awake);
}

TEST_F(ContactEvents, SleepingKeepsAContactAndRemovingABodyEndsIt) {
  make_floor(0.0);
  const BodyId lower = make_box({0.0, 0.5 + 1.0e-6});
  const BodyId upper = make_box({0.0, 1.5 + 2.0e-6});
  world_.set_contact_events(true);
  run(120);
  ASSERT_FALSE(state(lower).awake);
  ASSERT_FALSE(state(upper).awake);
  // Two begins (floor-lower, lower-upper), in pair order, and nothing as they slept.
  ASSERT_EQ(seen_.size(), 2u);
  EXPECT_EQ(seen_[0].step, 1u);
  EXPECT_EQ(seen_[0].b, lower);
  EXPECT_EQ(seen_[1].a, lower);
  EXPECT_EQ(seen_[1].b, upper);
  EXPECT_EQ(world_.contacts_in_touch(), 2u);
  ASSERT_TRUE(world_.remove_body(upper));
  const std::uint64_t step_after = world_.step_count() + 1;
  run(1);
  ASSERT_EQ(seen_.size(), 3u);
  EXPECT_EQ(seen_[2].kind, ContactEventKind::End);
  EXPECT_EQ(seen_[2].step, step_after);
  EXPECT_EQ(seen_[2].a, lower);
  EXPECT_EQ(seen_[2].b, upper);
  EXPECT_EQ(world_.contacts_in_touch(), 1u);
}

// A rain of circles and boxes into a container, with sub-steps: many contacts
// beginning and ending between moving bodies, swept hits, and sleep.
void rain(World& world) {
  add_or_fail(world, box_def({0.0, -0.5}, {8.0, 0.5}, Motion::Static));
  add_or_fail(world, box_def({-8.5, 10.0}, {0.5, 10.0}, Motion::Static));
  add_or_fail(world, box_def({8.5, 10.0}, {0.5, 10.0}, Motion::Static));
  Rain r;
  for (int i = 0; i < 150; ++i) {
    const Vec2 at{-7.0 + (i % 14) + r.uniform(-0.1, 0.1), 1.0 + 1.2 * (i / 14)};
    BodyDef def = i % 3 == 0 ? box_def(at, {0.4, 0.3}) : circle_def(at, 0.45);
    def.velocity = {r.uniform(-2.0, 2.0), r.uniform(-1.0, 0.0)};
    def.restitution = i % 2 == 0 ? 0.3 : 0.0;
    add_or_fail(world, def);
  }
}

StageCounters without_contact_counters(StageCounters c) {
  c.contact_pair_tests = 0;
  c.contact_events = 0;
  return c;
}

TEST(ContactEventsRain, TwoRunsGiveTheSameEventsAndOffChangesNothingButTheirCost) {
  WorldSettings settings;
  settings.substeps = 2;
  World first(settings);
  World second(settings);
  World off(settings);
  rain(first);
  rain(second);
  rain(off);
  first.set_contact_events(true);
  second.set_contact_events(true);
  std::size_t begins = 0;
  std::size_t ends = 0;
  for (int step = 1; step <= 600; ++step) {
    first.step(kDt);
    second.step(kDt);
    off.step(kDt);
    ASSERT_EQ(first.contact_events(), second.contact_events()) << "step " << step;
    ASSERT_TRUE(off.contact_events().empty());
    ASSERT_EQ(first.state_hash(), off.state_hash()) << "step " << step;
    for (const ContactEvent& e : first.contact_events()) {
      ASSERT_EQ(e.step, static_cast<std::uint64_t>(step));
      ASSERT_LT(e.a.index, e.b.index);
      ASSERT_NEAR(length(e.normal), 1.0, 1.0e-12);
      (e.kind == ContactEventKind::Begin ? begins : ends) += 1;
    }
  }
  EXPECT_GT(begins, 150u);
  EXPECT_GT(ends, 50u);
  EXPECT_EQ(begins - ends, first.contacts_in_touch());
  EXPECT_EQ(first.counters().contact_events, begins + ends);
  EXPECT_GT(first.counters().contact_pair_tests, 0u);
  // Off, no stage did any work for events; every other counter is the same on.
  EXPECT_EQ(off.counters().contact_pair_tests, 0u);
  EXPECT_EQ(off.counters().contact_events, 0u);
  EXPECT_EQ(without_contact_counters(first.counters()), off.counters());
}

TEST(ContactEventsRain, SwitchingOffForgetsAndSwitchingOnStartsFromNoContact) {
  World world;
  rain(world);
  world.set_contact_events(true);
  for (int i = 0; i < 120; ++i) world.step(kDt);
  ASSERT_GT(world.contacts_in_touch(), 0u);
  world.set_contact_events(false);
  EXPECT_EQ(world.contacts_in_touch(), 0u);
  world.step(kDt);
  EXPECT_TRUE(world.contact_events().empty());
  const std::uint64_t tests = world.counters().contact_pair_tests;
  world.step(kDt);
  EXPECT_EQ(world.counters().contact_pair_tests, tests);
  world.set_contact_events(true);
  world.step(kDt);
  // Every pair seen touching is new: only begins.
  ASSERT_FALSE(world.contact_events().empty());
  for (const ContactEvent& e : world.contact_events()) {
    EXPECT_EQ(e.kind, ContactEventKind::Begin);
  }
}

}  // namespace
}  // namespace phys::testing
