// The frictionless velocity iterations in SIMD lanes (server/core/src/contact_lanes.h)
// must give the scalar pass's results bit for bit: the same velocities, the same
// accumulated impulses, the same answer to "did anything change".
#include "contact_lanes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "physics/world.h"
#include "rain.h"
#include "world_impl.h"

namespace phys::testing {
namespace {

// The scalar pass without friction (StepRunner::solve_contact), restated as the
// oracle: contacts one at a time in their order. A restatement shares any error of
// what it restates, so HandComputedContacts below checks both it and the lanes
// against impulses worked out by hand.
bool solve_in_order(std::vector<ContactRecord>& contacts,
                    const std::vector<ContactWeights>& weights, std::vector<Vec2>& velocity,
                    bool first_iteration) {
  bool changed = false;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    ContactRecord& k = contacts[i];
    Vec2 none{};
    Vec2& va = velocity[k.lower_pos];
    Vec2& vb = k.fixed ? none : velocity[k.upper_pos];
    const double wa = weights[i].lower;
    const double wb = weights[i].upper;
    const double mass = 1.0 / (wa + wb);
    double closing = dot((k.fixed ? Vec2{} : vb) - va, k.normal);
    if (wa == 0.0 && !k.fixed) closing += std::max(dot(va, k.normal), 0.0);
    if (wb == 0.0 && !k.fixed) closing -= std::min(dot(vb, k.normal), 0.0);
    if (wa + wb <= 0.0) continue;
    if (first_iteration && k.warm > 0.0) {
      k.impulse = k.warm;
      va -= k.normal * (k.impulse * wa);
      if (!k.fixed) vb += k.normal * (k.impulse * wb);
      changed = true;
      continue;
    }
    const double wanted = std::max(k.impulse + (k.target - closing) * mass, 0.0);
    const double impulse = wanted - k.impulse;
    k.impulse = wanted;
    va -= k.normal * (impulse * wa);
    if (!k.fixed) vb += k.normal * (impulse * wb);
    changed = changed || std::fabs(impulse) > 1.0e-12;
  }
  return changed;
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

struct Case {
  std::vector<ContactRecord> contacts;
  std::vector<ContactWeights> weights;
  std::vector<Vec2> velocity;  // bodies, then the zero the fixed lanes read
};

// Contacts grouped by their lower body, as the step makes them: many share bodies,
// some are against fixed bodies, some have one side carried (weight 0), a few
// have both (they change nothing), some start warm.
Case random_case(std::uint32_t bodies, int per_body, std::uint64_t seed) {
  Rain rain;
  for (std::uint64_t i = 0; i < seed; ++i) rain.uniform(0.0, 1.0);
  Case c;
  c.velocity.resize(bodies + 1);
  for (std::uint32_t b = 0; b < bodies; ++b) {
    c.velocity[b] = {rain.uniform(-3.0, 3.0), rain.uniform(-3.0, 3.0)};
  }
  for (std::uint32_t lower = 0; lower < bodies; ++lower) {
    for (int n = 0; n < per_body; ++n) {
      ContactRecord k{};
      k.lower_pos = lower;
      k.fixed = rain.uniform(0.0, 1.0) < 0.15 || lower + 1 == bodies;
      const auto reach = static_cast<std::uint32_t>(rain.uniform(1.0, 40.0));
      k.upper_pos = k.fixed ? 0 : std::min(bodies - 1, lower + reach);
      const double angle = rain.uniform(-3.2, 3.2);
      k.normal = {std::cos(angle), std::sin(angle)};
      k.target = rain.uniform(0.0, 1.0) < 0.5 ? 0.0 : rain.uniform(-0.5, 2.0);
      k.warm = rain.uniform(0.0, 1.0) < 0.3 ? rain.uniform(0.0, 0.5) : 0.0;
      k.impulse = 0.0;
      double wa = rain.uniform(0.2, 2.0);
      double wb = k.fixed ? 0.0 : rain.uniform(0.2, 2.0);
      const double carried = rain.uniform(0.0, 1.0);
      if (!k.fixed && carried < 0.2) wa = 0.0;
      if (!k.fixed && carried > 0.8) wb = 0.0;
      if (!k.fixed && carried > 0.98) wa = 0.0;  // both: the contact changes nothing
      c.contacts.push_back(k);
      c.weights.push_back({wa, wb});
    }
  }
  return c;
}

void expect_lanes_match_order(Case c, int iterations) {
  const auto bodies = static_cast<std::uint32_t>(c.velocity.size() - 1);
  Case oracle = c;
  ContactLanes lanes;
  lanes.pack(c.contacts, c.weights, bodies);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    const bool expected =
        solve_in_order(oracle.contacts, oracle.weights, oracle.velocity, iteration == 0);
    EXPECT_EQ(lanes.iterate(c.velocity.data(), iteration == 0), expected) << iteration;
  }
  lanes.unpack(c.contacts);
  for (std::uint32_t b = 0; b <= bodies; ++b) {
    ASSERT_TRUE(same_bits(c.velocity[b].x, oracle.velocity[b].x)) << "body " << b;
    ASSERT_TRUE(same_bits(c.velocity[b].y, oracle.velocity[b].y)) << "body " << b;
  }
  for (std::size_t i = 0; i < c.contacts.size(); ++i) {
    ASSERT_TRUE(same_bits(c.contacts[i].impulse, oracle.contacts[i].impulse)) << "contact " << i;
  }
}

// Contacts whose outcome follows from the contact law alone (after the impulse the
// pair closes at no more than its target, and the impulse never pulls), worked out
// by hand. Velocities are of bodies 0 to 3; normals point from lower to upper.
//   0: body 0 falls at (1, -3) onto a fixed floor, normal (0, -1), weight 1:
//      closing = (0 - v0).n = -3, impulse = (0 - -3) * 1 = 3, v0 = (1, -3) - 3 (0, -1)
//      = (1, 0): the fall stops, the slide is kept;
//   1: bodies 1 (lower, at (0, 1)) and 2 (upper, at (0, -1)) meet head on, normal
//      (0, 1), weights 1 and 1 (mass 1/2): closing = (-1 - 1) = -2, impulse = 2 * 1/2
//      = 1, v1 = (0, 1) - 1 (0, 1) = 0 and v2 = (0, -1) + 1 (0, 1) = 0: equal masses
//      stop, momentum (0 before) kept;
//   2: body 3 rests on the floor, normal (0, -1), target 1 m/s apart: closing 0,
//      impulse (1 - 0) * 1 = 1, v3 = (0, 0) - 1 (0, -1) = (0, 1);
// Another iteration changes no impulse (each contact now closes at its target),
// so it reports no change.
TEST(ContactLanes, HandComputedContacts) {
  if (!kHaveContactLanes) GTEST_SKIP() << "no SSE2";
  Case c;
  c.velocity = {{1.0, -3.0}, {0.0, 1.0}, {0.0, -1.0}, {0.0, 0.0}, {}};
  const auto contact = [&](std::uint32_t lower, std::uint32_t upper, bool fixed, Vec2 n,
                           double target, ContactWeights w) {
    ContactRecord k{};
    k.lower_pos = lower;
    k.upper_pos = upper;
    k.fixed = fixed;
    k.normal = n;
    k.target = target;
    c.contacts.push_back(k);
    c.weights.push_back(w);
  };
  contact(0, 0, true, {0.0, -1.0}, 0.0, {1.0, 0.0});
  contact(1, 2, false, {0.0, 1.0}, 0.0, {1.0, 1.0});
  contact(3, 0, true, {0.0, -1.0}, 1.0, {1.0, 0.0});
  const std::vector<Vec2> want_velocity = {{1.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}, {0.0, 1.0}};
  const std::vector<double> want_impulse = {3.0, 1.0, 1.0};

  Case oracle = c;
  EXPECT_TRUE(solve_in_order(oracle.contacts, oracle.weights, oracle.velocity, true));
  EXPECT_FALSE(solve_in_order(oracle.contacts, oracle.weights, oracle.velocity, false));
  ContactLanes lanes;
  lanes.pack(c.contacts, c.weights, 4);
  EXPECT_TRUE(lanes.iterate(c.velocity.data(), true));
  EXPECT_FALSE(lanes.iterate(c.velocity.data(), false));
  lanes.unpack(c.contacts);
  for (std::uint32_t b = 0; b < 4; ++b) {
    EXPECT_EQ(c.velocity[b], want_velocity[b]) << "lanes, body " << b;
    EXPECT_EQ(oracle.velocity[b], want_velocity[b]) << "oracle, body " << b;
  }
  for (std::size_t i = 0; i < want_impulse.size(); ++i) {
    EXPECT_EQ(c.contacts[i].impulse, want_impulse[i]) << "lanes, contact " << i;
    EXPECT_EQ(oracle.contacts[i].impulse, want_impulse[i]) << "oracle, contact " << i;
  }
  EXPECT_EQ(c.velocity[4], Vec2{}) << "the shared zero of the fixed lanes";
}

// Separating pairs and warm starts, by hand:
//   body 0 leaves the floor at (0, 2), normal (0, -1): closing = (0 - v0).n =
//   (0, -2).(0, -1) = +2 (separating), impulse max(0 + (0 - 2) * 1, 0) = 0: unchanged;
//   body 1 on the floor at rest, warm impulse 0.5: the first iteration applies it
//   whatever the velocity, v1 = (0, 0) - 0.5 (0, -1) = (0, 0.5); the second finds
//   closing = (0, -0.5).(0, -1) = +0.5, impulse max(0.5 + (0 - 0.5) * 1, 0) = 0:
//   the warm impulse is taken back, v1 = (0, 0.5) + 0.5 (0, -1) = 0.
TEST(ContactLanes, HandComputedSeparationAndWarmStart) {
  if (!kHaveContactLanes) GTEST_SKIP() << "no SSE2";
  Case c;
  c.velocity = {{0.0, 2.0}, {0.0, 0.0}, {}};
  for (std::uint32_t b = 0; b < 2; ++b) {
    ContactRecord k{};
    k.lower_pos = b;
    k.fixed = true;
    k.normal = {0.0, -1.0};
    k.warm = b == 1 ? 0.5 : 0.0;
    c.contacts.push_back(k);
    c.weights.push_back({1.0, 0.0});
  }
  ContactLanes lanes;
  lanes.pack(c.contacts, c.weights, 2);
  EXPECT_TRUE(lanes.iterate(c.velocity.data(), true));
  EXPECT_EQ(c.velocity[0], (Vec2{0.0, 2.0}));
  EXPECT_EQ(c.velocity[1], (Vec2{0.0, 0.5}));
  EXPECT_TRUE(lanes.iterate(c.velocity.data(), false));
  EXPECT_EQ(c.velocity[0], (Vec2{0.0, 2.0}));
  EXPECT_EQ(c.velocity[1], (Vec2{0.0, 0.0}));
  lanes.unpack(c.contacts);
  EXPECT_EQ(c.contacts[0].impulse, 0.0);
  EXPECT_EQ(c.contacts[1].impulse, 0.0);
}

TEST(ContactLanes, MatchTheScalarPassBitForBit) {
  if (!kHaveContactLanes) GTEST_SKIP() << "no SSE2: the step keeps the scalar pass";
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    SCOPED_TRACE(seed);
    expect_lanes_match_order(random_case(300, 3, seed), 8);
  }
}

TEST(ContactLanes, ContactsSharingABodyComeInTheirOrder) {
  if (!kHaveContactLanes) GTEST_SKIP() << "no SSE2";
  // A chain 0-1, 1-2, 2-3, ...: each contact needs the one before, so there is one
  // level per contact, and the lanes must not run any two together.
  Case c;
  const std::uint32_t bodies = 9;
  c.velocity.assign(bodies + 1, Vec2{});
  c.velocity[0] = {0.0, -4.0};
  for (std::uint32_t b = 0; b + 1 < bodies; ++b) {
    ContactRecord k{};
    k.lower_pos = b;
    k.upper_pos = b + 1;
    k.normal = {0.0, 1.0};
    c.contacts.push_back(k);
    c.weights.push_back({1.0, 1.0});
  }
  ContactLanes lanes;
  lanes.pack(c.contacts, c.weights, bodies);
  EXPECT_EQ(lanes.levels(), bodies - 1);
  expect_lanes_match_order(c, 3);
}

TEST(ContactLanes, FixedAndEmptyLanesLeaveTheSharedZeroAlone) {
  if (!kHaveContactLanes) GTEST_SKIP() << "no SSE2";
  // Three contacts against fixed bodies (one level, so one pair and an empty
  // lane), one with a NaN target: the zero velocity all of them read must stay
  // zero, or every later fixed contact would see a moving floor.
  Case c;
  c.velocity = {{0.0, -2.0}, {1.0, -3.0}, {0.5, 0.5}, {}};
  for (std::uint32_t b = 0; b < 3; ++b) {
    ContactRecord k{};
    k.lower_pos = b;
    k.fixed = true;
    k.normal = {0.0, -1.0};
    k.target = b == 1 ? std::numeric_limits<double>::quiet_NaN() : 0.0;
    c.contacts.push_back(k);
    c.weights.push_back({1.0, 0.0});
  }
  expect_lanes_match_order(c, 2);
  ContactLanes lanes;
  lanes.pack(c.contacts, c.weights, 3);
  lanes.iterate(c.velocity.data(), true);
  EXPECT_TRUE(same_bits(c.velocity[3].x, 0.0));
  EXPECT_TRUE(same_bits(c.velocity[3].y, 0.0));
}

// End to end: a frictionless pile (every velocity iteration in lanes) ends on the
// state hash that the scalar pass gives for it (recorded from the scalar pass alone).
// Mixed masses, so that the weights differ; shock propagation on (the default).
TEST(ContactLanes, FrictionlessPileEndsOnTheScalarPassHash) {
  World world;
  BodyDef floor;
  floor.motion = Motion::Static;
  floor.position = {0.0, -0.5};
  floor.half_extents = {16.0, 0.5};
  world.add_body(floor);
  for (const double x : {-16.5, 16.5}) {
    BodyDef wall = floor;
    wall.position = {x, 20.0};
    wall.half_extents = {0.5, 20.0};
    world.add_body(wall);
  }
  Rain rain;
  for (int n = 0; n < 600; ++n) {
    BodyDef circle;
    circle.shape = Shape::Circle;
    circle.radius = 0.5;
    circle.mass = 1.0 + (n % 3);
    circle.position = {-14.4 + 1.2 * (n % 25) + rain.uniform(-0.1, 0.1), 1.0 + 1.2 * (n / 25)};
    circle.velocity = {rain.uniform(-1.0, 1.0), 0.0};
    world.add_body(circle);
  }
  for (int step = 0; step < 300; ++step) world.step(1.0 / 60.0);
  EXPECT_GT(world.counters().restitution_passes, 0u);
  EXPECT_EQ(world.state_hash(), 0x66a57d73d17f9878ull)
      << "state hash is 0x" << std::hex << world.state_hash();
}

}  // namespace
}  // namespace phys::testing
