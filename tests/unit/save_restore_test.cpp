// Saved and restored world state (World::save, World::restore): restore, then step,
// equals the steps the saved world took, bit for bit, on every scene of the scene
// library; the counters keep counting; a world changed in any way since the save
// (bodies added and removed, contact events switched) goes back exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "physics/world.h"
#include "physics_test_support.h"
#include "rollback_check.h"
#include "scenes/scenes.h"

namespace phys::testing {
namespace {

struct LibraryScene {
  std::string label;
  scenes::SceneSpec scene;
  int save_at;  // steps before the save: mid-fall, mid-settle, or settled
};

std::vector<LibraryScene> library_scenes() {
  using scenes::StageVariant;
  return {
      {"rain_4000", scenes::rain_scene(4000, 1, 0, 0), 40},
      {"pile_1000", scenes::pile_scene(1000), 90},
      {"rained_300_in_20m", scenes::rained_circles_scene({20.0, 300, 0.5, 0}), 120},
      {"pyramid_1275", scenes::pyramid_scene(50, 1), 30},
      {"column_50", scenes::column_scene(50, false, 1), 60},
      {"column_mass_10", scenes::column_scene(10, true, 1), 200},
      {"bounce", scenes::bounce_scene(0.5, 1), 25},
      {"projectile", scenes::projectile_scene(0.8), 10},
      {"friction_decay", scenes::friction_decay_scene(0.1), 10},
      {"stages_all", scenes::stages_scene(StageVariant::All, 1), 20},
      {"stages_boxes_only", scenes::stages_scene(StageVariant::BoxesOnly, 1), 20},
  };
}

World world_of(const scenes::SceneSpec& scene) {
  WorldSettings settings;
  settings.gravity = scene.gravity;
  World world(settings);
  scenes::add_to_world(world, scene);
  return world;
}

class SaveRestoreLibrary : public ::testing::TestWithParam<LibraryScene> {};

TEST_P(SaveRestoreLibrary, RestoreThenStepEqualsTheSavedWorldsSteps) {
  World world = world_of(GetParam().scene);
  for (int i = 0; i < GetParam().save_at; ++i) world.step(kDt);
  expect_restore_replays(world, 30, kDt);
}

TEST_P(SaveRestoreLibrary, WithContactEventsTheSameEventsFollow) {
  World world = world_of(GetParam().scene);
  world.set_contact_events(true);
  for (int i = 0; i < GetParam().save_at; ++i) world.step(kDt);
  const SavedWorld saved = world.save();
  std::vector<std::vector<ContactEvent>> first;
  for (int i = 0; i < 10; ++i) {
    world.step(kDt);
    first.push_back(world.contact_events());
  }
  world.restore(saved);
  for (int i = 0; i < 10; ++i) {
    world.step(kDt);
    ASSERT_EQ(world.contact_events().size(), first[i].size()) << "step " << i;
    for (std::size_t e = 0; e < first[i].size(); ++e) {
      EXPECT_EQ(world.contact_events()[e].a, first[i][e].a);
      EXPECT_EQ(world.contact_events()[e].b, first[i][e].b);
      EXPECT_EQ(world.contact_events()[e].kind, first[i][e].kind);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, SaveRestoreLibrary, ::testing::ValuesIn(library_scenes()),
                         [](const auto& param_info) { return param_info.param.label; });

TEST(SaveRestore, AWorldChangedSinceTheSaveGoesBackExactly) {
  World world = world_of(scenes::pile_scene(1000));
  for (int i = 0; i < 30; ++i) world.step(kDt);
  const SavedWorld saved = world.save();
  const std::vector<BodyState> at_save = world.bodies();
  const std::vector<std::uint64_t> first = hashes_of_steps(world, 20, kDt);

  // Bodies removed and added (a slot reused with a new generation), one teleported
  // and one pushed, and the contact events switched on.
  world.restore(saved);
  ASSERT_TRUE(world.remove_body(at_save[10].id));
  ASSERT_TRUE(world.remove_body(at_save[500].id));
  const BodyId added = world.add_body(circle_def({0.0, 40.0}, 0.5));
  ASSERT_TRUE(added.is_valid());
  ASSERT_TRUE(world.set_position(at_save[700].id, {3.0, 30.0}));
  ASSERT_TRUE(world.set_velocity(at_save[800].id, {-4.0, 2.0}));
  world.set_contact_events(true);
  hashes_of_steps(world, 7, kDt);

  world.restore(saved);
  EXPECT_FALSE(world.contains(added));
  EXPECT_TRUE(world.contains(at_save[10].id));
  EXPECT_FALSE(world.contact_events_on());
  EXPECT_EQ(world.bodies().size(), at_save.size());
  EXPECT_EQ(hashes_of_steps(world, 20, kDt), first);
}

TEST(SaveRestore, SaveIntoReusesTheTargetAndRestoresTheLatestSave) {
  World world = world_of(scenes::rain_scene(1000, 1, 0, 0));
  SavedWorld slot;
  EXPECT_TRUE(slot.empty());
  EXPECT_EQ(slot.bytes(), 0u);
  std::uint64_t hash_at_last_save = 0;
  for (int tick = 0; tick < 40; ++tick) {
    if (tick % 10 == 0) {
      world.save_into(slot);
      hash_at_last_save = world.state_hash();
    }
    world.step(kDt);
  }
  EXPECT_EQ(slot.step_count(), 30u);
  world.restore(slot);
  EXPECT_EQ(world.state_hash(), hash_at_last_save);
  EXPECT_EQ(world.step_count(), 30u);
  // 1,003 bodies of at least a Body each (128 bytes): the figure is of the state.
  EXPECT_GT(slot.bytes(), 1003u * 128u);
}

TEST(SaveRestore, ACopiedSaveIsIndependentOfItsSource) {
  World world = world_of(scenes::column_scene(10, false, 1));
  SavedWorld a = world.save();
  const std::uint64_t hash_a = world.state_hash();
  SavedWorld b = a;  // copy
  hashes_of_steps(world, 15, kDt);
  world.save_into(a);  // a moves on; b must not
  world.restore(b);
  EXPECT_EQ(world.state_hash(), hash_a);
  world.restore(a);
  EXPECT_EQ(world.step_count(), 15u);
}

TEST(SaveRestore, CountersKeepCountingAcrossARestore) {
  World world = world_of(scenes::pile_scene(1000));
  const SavedWorld saved = world.save();
  hashes_of_steps(world, 10, kDt);
  ASSERT_EQ(world.counters().steps, 10u);
  world.restore(saved);
  EXPECT_EQ(world.counters().steps, 10u);
  EXPECT_EQ(world.step_count(), 0u);
  hashes_of_steps(world, 10, kDt);
  EXPECT_EQ(world.counters().steps, 20u);
  EXPECT_EQ(world.step_count(), 10u);
  // A fresh World from a save starts its counters at zero.
  World fresh(saved);
  EXPECT_EQ(fresh.counters().steps, 0u);
}

// Bytes that are not a world this core wrote: each refused with a reason, never a
// crash, never a world that steps on garbage.
TEST(WorldBytes, EveryDamagedFormIsRefusedWithAReason) {
  World world = world_of(scenes::pile_scene(100));
  world.set_contact_events(true);
  for (int i = 0; i < 30; ++i) world.step(kDt);
  const std::vector<std::uint8_t> good = world.to_bytes();
  std::string error;
  ASSERT_TRUE(World::from_bytes(good, &error).has_value()) << error;

  // Cut short anywhere: at every length up to the whole.
  std::size_t refused = 0;
  const std::size_t stride = std::max<std::size_t>(1, good.size() / 2000);
  for (std::size_t n = 0; n < good.size(); n += stride) {
    error.clear();
    const auto cut = World::from_bytes(std::span(good.data(), n), &error);
    EXPECT_FALSE(cut.has_value()) << n << " bytes";
    EXPECT_FALSE(error.empty());
    ++refused;
  }
  EXPECT_GT(refused, 100u);

  const auto refused_because = [](std::vector<std::uint8_t> bytes) {
    std::string why;
    const auto loaded = World::from_bytes(bytes, &why);
    return loaded.has_value() ? std::string("accepted") : why;
  };
  std::vector<std::uint8_t> bytes = good;
  bytes[0] = 'q';
  EXPECT_NE(refused_because(bytes).find("tag"), std::string::npos);
  bytes = good;
  bytes[8] = 9;  // version
  EXPECT_NE(refused_because(bytes).find("version 9"), std::string::npos);
  bytes = good;
  bytes.push_back(0);
  EXPECT_NE(refused_because(bytes).find("left over"), std::string::npos);
  // The body count (after the tag, the version, the settings and the step count)
  // made huge: refused before anything is allocated for it.
  bytes = good;
  const std::size_t settings_bytes =
      16 + 1 + 4 + 8 + 4 + 4 + 4 + 8 * 3 + 1 + 8 * 2 + 1 + 32 + 8 + 4 + 3;
  const std::size_t count_at = 8 + 4 + settings_bytes + 8;
  std::uint64_t count = 0;
  std::memcpy(&count, bytes.data() + count_at, 8);
  ASSERT_EQ(count, world.bodies().size()) << "the body count's place in the bytes";
  count = UINT64_MAX / 2;
  std::memcpy(bytes.data() + count_at, &count, 8);
  EXPECT_NE(refused_because(bytes).find("longer than the bytes left"), std::string::npos);
  // A flag that is neither 0 nor 1 (the first body's `alive`).
  bytes = good;
  const std::size_t alive_at = count_at + 8 + 4 * 16 + 2 * 8 + 2;
  ASSERT_EQ(bytes[alive_at], 1);
  bytes[alive_at] = 7;
  EXPECT_NE(refused_because(bytes).find("neither 0 nor 1"), std::string::npos);
  // A non-finite position.
  bytes = good;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(bytes.data() + count_at + 8, &nan, 8);
  EXPECT_NE(refused_because(bytes).find("non-finite"), std::string::npos);
  // Random bytes flipped anywhere: refused, or a world whose bytes are read back as
  // they were (never a crash: AddressSanitizer runs this suite too).
  std::uint64_t seed = 12345;
  for (int trial = 0; trial < 300; ++trial) {
    bytes = good;
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    bytes[(seed >> 33) % bytes.size()] ^= static_cast<std::uint8_t>(1u << ((seed >> 20) % 8));
    std::string why;
    const auto loaded = World::from_bytes(bytes, &why);
    if (loaded) {
      EXPECT_EQ(loaded->to_bytes(), bytes);
    } else {
      EXPECT_FALSE(why.empty());
    }
  }
}

}  // namespace
}  // namespace phys::testing
