// Body ids: bodies added and removed while the world steps, stale ids refused
// everywhere, freed slots reused under a new generation, ids that survive packing.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

class BodyIds : public WorldTest {};

TEST_F(BodyIds, AddedBodiesAreDistinctAndFound) {
  const BodyId a = make_box({0.0, 0.0});
  const BodyId b = make_circle({3.0, 0.0});
  EXPECT_NE(a, b);
  EXPECT_TRUE(world_.contains(a));
  EXPECT_TRUE(world_.contains(b));
  EXPECT_EQ(world_.body_count(), 2u);
  EXPECT_EQ(state(b).shape, Shape::Circle);
  EXPECT_EQ(state(b).id, b);
}

TEST_F(BodyIds, RemovedIdIsStaleEverywhere) {
  const BodyId a = make_box({0.0, 0.0});
  ASSERT_TRUE(world_.remove_body(a));
  EXPECT_FALSE(world_.contains(a));
  EXPECT_FALSE(world_.body(a).has_value());
  EXPECT_FALSE(world_.remove_body(a));
  EXPECT_FALSE(world_.set_acceleration(a, {1.0, 0.0}));
  EXPECT_FALSE(world_.set_position(a, {1.0, 0.0}));
  EXPECT_FALSE(world_.set_velocity(a, {1.0, 0.0}));
  EXPECT_EQ(world_.body_count(), 0u);
}

TEST_F(BodyIds, InvalidAndMadeUpIdsAreRefused) {
  make_box({0.0, 0.0});
  EXPECT_FALSE(world_.contains(BodyId::invalid()));
  EXPECT_FALSE(world_.remove_body(BodyId::invalid()));
  EXPECT_FALSE(world_.contains(BodyId{12345, 0}));
  EXPECT_FALSE(world_.set_acceleration(BodyId{12345, 0}, {1.0, 0.0}));
  EXPECT_EQ(world_.body_count(), 1u);
}

TEST_F(BodyIds, AFreedSlotIsReusedWithANewGeneration) {
  const BodyId old_id = make_box({0.0, 0.0});
  ASSERT_TRUE(world_.remove_body(old_id));
  const BodyId new_id = make_circle({5.0, 5.0});
  EXPECT_EQ(new_id.index, old_id.index);
  EXPECT_NE(new_id.generation, old_id.generation);
  // The old id must not reach the new body.
  EXPECT_FALSE(world_.contains(old_id));
  EXPECT_FALSE(world_.set_velocity(old_id, {9.0, 9.0}));
  EXPECT_FALSE(world_.remove_body(old_id));
  EXPECT_TRUE(world_.contains(new_id));
  EXPECT_EQ(velocity(new_id), (Vec2{}));
}

TEST_F(BodyIds, AddingAndRemovingWhileSteppingKeepsTheOthersIntact) {
  make_floor(0.0);
  std::vector<BodyId> live;
  std::uint64_t removed = 0;
  for (int step = 0; step < 300; ++step) {
    if (step % 3 == 0) live.push_back(make_circle({-20.0 + 0.37 * (step % 100), 8.0}, 0.3));
    if (step % 7 == 0 && live.size() > 4) {
      // Remove the second oldest, so removals hit the middle of the storage.
      ASSERT_TRUE(world_.remove_body(live[1]));
      live.erase(live.begin() + 1);
      ++removed;
    }
    world_.step(kDt);
    for (const BodyId id : live) ASSERT_TRUE(world_.contains(id)) << "step " << step;
  }
  EXPECT_EQ(world_.body_count(), live.size() + 1);  // plus the floor
  EXPECT_EQ(world_.dynamic_body_count(), live.size());
  EXPECT_GT(removed, 0u);
  EXPECT_TRUE(all_finite(world_.bodies()));
}

TEST_F(BodyIds, BodiesComeOutInAscendingIdOrder) {
  std::vector<BodyId> ids;
  for (int i = 0; i < 10; ++i) ids.push_back(make_box({2.0 * i, 0.0}));
  world_.remove_body(ids[3]);
  world_.remove_body(ids[6]);
  make_box({50.0, 0.0});  // reuses a freed slot
  const std::vector<BodyState> bodies = world_.bodies();
  ASSERT_EQ(bodies.size(), 9u);
  for (std::size_t i = 1; i < bodies.size(); ++i) {
    EXPECT_LT(bodies[i - 1].id.index, bodies[i].id.index);
  }
  std::size_t visited = 0;
  world_.for_each_body([&](const BodyState&) { ++visited; });
  EXPECT_EQ(visited, bodies.size());
}

TEST(BodyIdPacking, RoundTripsThroughSixtyFourBits) {
  const BodyId id{0x12345678u, 0x9abcdef0u};
  EXPECT_EQ(BodyId::from_packed(id.packed()), id);
  EXPECT_EQ(id.packed(), 0x9abcdef012345678ull);
  EXPECT_FALSE(BodyId::invalid().is_valid());
  EXPECT_TRUE(id.is_valid());
}

}  // namespace
}  // namespace phys::testing
