// Every scene file in scenes/ saved mid-run and restored: restore, then step, takes
// exactly the steps the saved world took, and so does a fresh World built from the
// saved state (tests/unit/support/rollback_check.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <variant>
#include <vector>

#include "rollback_check.h"
#include "scene_test_support.h"

namespace scene {
namespace {

TEST(SaveRestoreScenes, EveryFileInScenesReplaysFromASave) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(testing::scenes_dir())) {
    if (entry.path().extension() == ".textproto") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 5u);
  for (const auto& file : files) {
    SCOPED_TRACE(file.filename().string());
    SceneResult result = load_scene_file(file);
    ASSERT_TRUE(std::holds_alternative<SceneDef>(result));
    const SceneDef& def = std::get<SceneDef>(result);
    phys::World world = build_world(def);
    const double dt = fixed_dt(def);
    for (int i = 0; i < 45; ++i) world.step(dt);
    phys::testing::expect_restore_replays(world, 30, dt);
  }
}

}  // namespace
}  // namespace scene
