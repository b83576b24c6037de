// Collision filtering (phys::Filter, Box2D's b2Filter): the rule itself, a body
// falling through what its mask leaves out, groups that always or never collide,
// and a random pile checked pair by pair against the rule, with and without
// filters: a pair the filters forbid never makes contact (and some of them pass
// through each other), a pair they allow never ends a step deep in each other.
#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "physics_test_support.h"
#include "scenes/random.h"

namespace phys::testing {
namespace {

Filter make_filter(std::uint32_t category, std::uint32_t mask, std::int32_t group = 0) {
  Filter f;
  f.category_bits = category;
  f.mask_bits = mask;
  f.group = group;
  return f;
}

TEST(ShouldCollide, FollowsBox2DsRule) {
  const Filter all{};
  EXPECT_TRUE(should_collide(all, all));
  // Masks: both must accept the other's category.
  EXPECT_FALSE(should_collide(make_filter(1, ~2u), make_filter(2, ~0u)));
  EXPECT_FALSE(should_collide(make_filter(2, ~0u), make_filter(1, ~2u)));
  EXPECT_TRUE(should_collide(make_filter(1, 2), make_filter(2, 1)));
  // The same positive group always collides, the same negative group never does.
  EXPECT_TRUE(should_collide(make_filter(1, 0, 3), make_filter(1, 0, 3)));
  EXPECT_FALSE(should_collide(make_filter(1, ~0u, -3), make_filter(1, ~0u, -3)));
  // Different groups fall back on the masks.
  EXPECT_TRUE(should_collide(make_filter(1, ~0u, -3), make_filter(1, ~0u, -4)));
  EXPECT_FALSE(should_collide(make_filter(1, 0, 3), make_filter(1, ~0u, 4)));
}

class Filtering : public WorldTest {};

TEST_F(Filtering, ABodyFallsThroughAFloorItsMaskLeavesOut) {
  BodyDef upper = box_def({0.0, 4.5}, {50.0, 0.5}, Motion::Static);
  upper.filter = make_filter(2, ~0u);
  add(upper);
  make_floor(-10.0);
  BodyDef box = box_def({0.0, 8.0}, {0.5, 0.5});
  box.filter = make_filter(1, ~2u);
  const BodyId passer = add(box);
  const BodyId stopped = add(box_def({3.0, 8.0}, {0.5, 0.5}));
  step_n(240);
  EXPECT_NEAR(position(passer).y, -9.5, 0.01);  // on the lower floor
  EXPECT_NEAR(position(stopped).y, 5.5, 0.01);  // on the upper one
}

TEST_F(Filtering, ANegativeGroupNeverCollidesWithItself) {
  make_floor(0.0);
  BodyDef box = box_def({0.0, 0.5}, {0.5, 0.5});
  box.filter.group = -1;
  const BodyId lower = add(box);
  box.position = {0.0, 3.0};
  const BodyId upper = add(box);
  step_n(180);
  // Both rest on the floor, one inside the other.
  EXPECT_NEAR(position(lower).y, 0.5, 0.01);
  EXPECT_NEAR(position(upper).y, 0.5, 0.01);
}

TEST_F(Filtering, APositiveGroupAlwaysCollidesWhateverTheMasks) {
  make_floor(0.0);
  BodyDef box = box_def({0.0, 0.5}, {0.5, 0.5});
  // Category 4, meeting the floor's category 1 only: the masks keep two such boxes
  // apart, and the group puts them together again.
  box.filter = make_filter(4, 1, 7);
  const BodyId lower = add(box);
  box.position = {0.0, 3.0};
  const BodyId upper = add(box);
  step_n(180);
  EXPECT_NEAR(position(lower).y, 0.5, 0.01);
  EXPECT_NEAR(position(upper).y, 1.5, 0.01);  // stacked: the group collides
  // Without the group, the masks keep them apart: the upper falls into the lower.
  reset(WorldSettings{});
  make_floor(0.0);
  box.filter.group = 0;
  box.position = {0.0, 0.5};
  add(box);
  box.position = {0.0, 3.0};
  const BodyId through = add(box);
  step_n(180);
  EXPECT_NEAR(position(through).y, 0.5, 0.01);
}

TEST_F(Filtering, SettingAFilterWakesTheBodyAndLetsItFall) {
  make_floor(0.0);
  const BodyId box = make_box({0.0, 0.5});
  step_n(240);  // at rest, and asleep
  ASSERT_FALSE(state(box).awake);
  const Filter no_floor = make_filter(2, ~1u);
  ASSERT_TRUE(world_.set_filter(box, no_floor));
  EXPECT_EQ(world_.filter(box), no_floor);
  step_n(60);
  EXPECT_LT(position(box).y, -3.0);  // a second of free fall
}

// A pile of random boxes and circles falling into a container, each in one of three
// categories with a random mask, some in groups. After every step, every pair is
// checked against the filters: contacts begin only between pairs that may collide,
// and no such pair is deep in another.
struct PileResult {
  std::size_t forbidden_contacts = 0;  // contact events between pairs that may not collide
  std::size_t deep_allowed = 0;        // allowed pairs deeper than kDeep after a step
  std::size_t deep_forbidden = 0;      // forbidden pairs deeper than kDeep (passing through)
  std::size_t allowed_contacts = 0;    // contact events between pairs that may
};
// m: twice the deepest overlap the same pile shows between colliding bodies without
// any filter (0.07 m, transient, in the impacts of its fall), and less than half
// of the smallest body: a pair deeper than this was let through.
constexpr double kDeep = 0.15;

PileResult run_pile(bool filtered) {
  World world;
  world.set_contact_events(true);
  add_or_fail(world, box_def({0.0, -0.5}, {10.0, 0.5}, Motion::Static));
  add_or_fail(world, box_def({-10.5, 10.0}, {0.5, 10.0}, Motion::Static));
  add_or_fail(world, box_def({10.5, 10.0}, {0.5, 10.0}, Motion::Static));
  scenes::Rain rain;
  std::vector<Filter> filters(3);  // the walls: default
  for (int i = 0; i < 150; ++i) {
    // Rows of ten, 1.8 m and 1 m apart, jittered: no two start inside each other.
    const Vec2 at{-8.1 + 1.8 * (i % 10) + rain.uniform(-0.3, 0.3),
                  1.0 + 1.0 * (i / 10) + rain.uniform(-0.05, 0.05)};
    BodyDef def = i % 2 == 0 ? box_def(at, {rain.uniform(0.2, 0.45), rain.uniform(0.2, 0.45)})
                             : circle_def(at, rain.uniform(0.2, 0.45));
    const auto category = static_cast<std::uint32_t>(1u << (2 * (i % 3) + 1));   // 2, 8, 32
    const auto mask = static_cast<std::uint32_t>(rain.uniform(0.0, 64.0)) | 1u;  // the walls
    const int group_pick = static_cast<int>(rain.uniform(0.0, 6.0));
    const std::int32_t group = group_pick == 0 ? -1 : group_pick == 1 ? 2 : 0;
    if (filtered) def.filter = make_filter(category, mask, group);
    filters.push_back(def.filter);
    add_or_fail(world, def);
  }
  PileResult result;
  for (int step = 0; step < 300; ++step) {
    world.step(kDt);
    for (const ContactEvent& e : world.contact_events()) {
      if (e.kind != ContactEventKind::Begin) continue;
      const bool allowed = should_collide(filters[e.a.index], filters[e.b.index]);
      ++(allowed ? result.allowed_contacts : result.forbidden_contacts);
    }
    const std::vector<BodyState> bodies = world.bodies();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      for (std::size_t j = i + 1; j < bodies.size(); ++j) {
        if (overlap_depth(bodies[i], bodies[j]) <= kDeep) continue;
        const bool allowed = should_collide(filters[i], filters[j]);
        ++(allowed ? result.deep_allowed : result.deep_forbidden);
      }
    }
  }
  return result;
}

TEST(FilteredPile, PairsCollideExactlyAsTheFiltersSay) {
  const PileResult r = run_pile(true);
  EXPECT_EQ(r.forbidden_contacts, 0u);
  EXPECT_EQ(r.deep_allowed, 0u);
  EXPECT_GT(r.allowed_contacts, 100u);  // the allowed pairs still meet
  EXPECT_GT(r.deep_forbidden, 10u);     // and the forbidden ones pass through
}

TEST(FilteredPile, WithoutFiltersEveryPairCollides) {
  const PileResult r = run_pile(false);
  EXPECT_EQ(r.forbidden_contacts, 0u);
  EXPECT_EQ(r.deep_forbidden, 0u);
  EXPECT_EQ(r.deep_allowed, 0u);
  EXPECT_GT(r.allowed_contacts, 100u);
}

}  // namespace
}  // namespace phys::testing
