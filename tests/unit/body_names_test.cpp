// Body names (BodyDef::name, World::find_body, World::name): found by name, the
// lowest id index among equal names, nothing for an unknown name or a removed body,
// and a reused slot named afresh.
#include <gtest/gtest.h>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

BodyDef named(Vec2 at, const char* name) {
  BodyDef def = box_def(at, {0.5, 0.5}, Motion::Static);
  def.name = name;
  return def;
}

TEST(BodyNames, FoundByNameAndGivenBack) {
  World world;
  add_or_fail(world, named({0.0, 0.0}, ""));
  const BodyId door = add_or_fail(world, named({2.0, 0.0}, "door"));
  const BodyId key = add_or_fail(world, named({4.0, 0.0}, "key"));
  EXPECT_EQ(world.find_body("door"), door);
  EXPECT_EQ(world.find_body("key"), key);
  EXPECT_EQ(world.name(door), "door");
  EXPECT_EQ(world.name(BodyId{0, 1}), "");
  EXPECT_EQ(world.find_body("lock"), std::nullopt);
  EXPECT_EQ(world.find_body(""), std::nullopt);  // unnamed bodies are not found
  EXPECT_EQ(world.find_body("doo"), std::nullopt);
}

TEST(BodyNames, EqualNamesGiveTheLowestIdIndex) {
  World world;
  const BodyId first = add_or_fail(world, named({0.0, 0.0}, "crate"));
  const BodyId second = add_or_fail(world, named({2.0, 0.0}, "crate"));
  EXPECT_EQ(world.find_body("crate"), first);
  ASSERT_TRUE(world.remove_body(first));
  EXPECT_EQ(world.find_body("crate"), second);
}

TEST(BodyNames, ARemovedBodyIsNotFoundAndItsSlotIsNamedAfresh) {
  World world;
  const BodyId door = add_or_fail(world, named({0.0, 0.0}, "door"));
  ASSERT_TRUE(world.remove_body(door));
  EXPECT_EQ(world.find_body("door"), std::nullopt);
  EXPECT_EQ(world.name(door), "");
  const BodyId again = add_or_fail(world, named({0.0, 0.0}, "gate"));  // reuses the slot
  ASSERT_EQ(again.index, door.index);
  EXPECT_EQ(world.find_body("door"), std::nullopt);
  EXPECT_EQ(world.find_body("gate"), again);
  EXPECT_EQ(world.name(again), "gate");
}

}  // namespace
}  // namespace phys::testing
