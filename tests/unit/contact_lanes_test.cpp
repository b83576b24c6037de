// The frictionless velocity iterations in SIMD lanes (server/core/src/contact_lanes.h)
// against impulses worked out by hand, and end to end against the one-at-a-time pass
// (tests/unit/solver_paths_test.cpp compares the two paths body by body).
#include "contact_lanes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "physics/world.h"
#include "scenes/random.h"
#include "world_impl.h"

namespace phys::testing {
namespace {

using scenes::Rain;

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

struct Case {
  std::vector<ContactRecord> contacts;
  std::vector<ContactWeights> weights;
  std::vector<Vec2> velocity;  // bodies, then the zero the fixed lanes read
};

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

  ContactLanes lanes;
  lanes.pack(c.contacts, c.weights, 4);
  EXPECT_TRUE(lanes.iterate(c.velocity.data(), true));
  EXPECT_FALSE(lanes.iterate(c.velocity.data(), false));
  lanes.unpack(c.contacts);
  for (std::uint32_t b = 0; b < 4; ++b) {
    EXPECT_EQ(c.velocity[b], want_velocity[b]) << "body " << b;
  }
  for (std::size_t i = 0; i < want_impulse.size(); ++i) {
    EXPECT_EQ(c.contacts[i].impulse, want_impulse[i]) << "contact " << i;
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

TEST(ContactLanes, ContactsSharingABodyComeInTheirOrder) {
  if (!kHaveContactLanes) GTEST_SKIP() << "no SSE2";
  // A chain 0-1, 1-2, 2-3, ...: each contact needs the one before, so there is one
  // level per contact, and the lanes must not run any two together. Body 0 rises
  // at 4 m/s into the chain at rest, normals up, equal weights: in order, each
  // contact leaves its pair moving together at half the lower body's speed
  // (impulse v/2), so one iteration ends with 2, 1, 1/2, ..., 1/64 and the last
  // body at 1/64, every value exact. Any two contacts run together would differ.
  Case c;
  const std::uint32_t bodies = 9;
  c.velocity.assign(bodies + 1, Vec2{});
  c.velocity[0] = {0.0, 4.0};
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
  EXPECT_TRUE(lanes.iterate(c.velocity.data(), true));
  lanes.unpack(c.contacts);
  double speed = 4.0;
  for (std::uint32_t b = 0; b + 1 < bodies; ++b) {
    EXPECT_EQ(c.contacts[b].impulse, speed / 2.0) << "contact " << b;
    speed /= 2.0;
    EXPECT_EQ(c.velocity[b], (Vec2{0.0, speed})) << "body " << b;
  }
  EXPECT_EQ(c.velocity[bodies - 1], (Vec2{0.0, speed}));
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
  ContactLanes lanes;
  lanes.pack(c.contacts, c.weights, 3);
  lanes.iterate(c.velocity.data(), true);
  EXPECT_TRUE(same_bits(c.velocity[3].x, 0.0));
  EXPECT_TRUE(same_bits(c.velocity[3].y, 0.0));
}

// End to end: a frictionless pile ends on its golden state hash with its velocity
// iterations in lanes and with the one-at-a-time pass (simd_contact_lanes off).
// Mixed masses, so that the weights differ; shock propagation on (the default).
std::uint64_t frictionless_pile_hash(bool lanes) {
  WorldSettings settings;
  settings.simd_contact_lanes = lanes;
  World world(settings);
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
  EXPECT_GT(world.counters().velocity_solves, 0u);
  return world.state_hash();
}

TEST(ContactLanes, FrictionlessPileEndsOnItsGoldenHashBothWays) {
  const std::uint64_t with_lanes = frictionless_pile_hash(true);
  const std::uint64_t one_at_a_time = frictionless_pile_hash(false);
  EXPECT_EQ(with_lanes, 0x66a57d73d17f9878ull) << "state hash is 0x" << std::hex << with_lanes;
  EXPECT_EQ(one_at_a_time, 0x66a57d73d17f9878ull)
      << "state hash is 0x" << std::hex << one_at_a_time;
}

}  // namespace
}  // namespace phys::testing
