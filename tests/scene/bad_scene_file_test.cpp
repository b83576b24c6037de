// Scene files that cannot be read as one (missing, a directory, empty, binary
// garbage, larger than the limit) are refused with the file's name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "scene_test_support.h"

namespace scene {
namespace {

using testing::scene_with;

class SceneFile : public ::testing::Test {
 protected:
  std::filesystem::path write(const std::string& name, const std::string& bytes) {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("scene_tests_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

SceneError load_error(const std::filesystem::path& path) {
  SceneResult result = load_scene_file(path);
  if (const auto* error = std::get_if<SceneError>(&result)) return *error;
  ADD_FAILURE() << path << " was accepted";
  return {};
}

TEST_F(SceneFile, MissingFileIsRefused) {
  const SceneError error = load_error(dir_ / "missing.textproto");
  EXPECT_EQ(error.file, (dir_ / "missing.textproto").string());
  EXPECT_NE(error.message.find("cannot open"), std::string::npos) << error.message;
}

TEST_F(SceneFile, DirectoryIsRefused) {
  EXPECT_NE(load_error(dir_).message.find("not a regular file"), std::string::npos);
}

TEST_F(SceneFile, EmptyFileIsRefused) {
  const SceneError error = load_error(write("empty.textproto", ""));
  EXPECT_NE(error.message.find("empty"), std::string::npos) << error.message;
}

TEST_F(SceneFile, GarbageBytesAreRefusedWithALine) {
  std::string bytes = "\x89PNG\r\n\x1a\n";
  for (int i = 0; i < 256; ++i) bytes += static_cast<char>(i);
  const SceneError error = load_error(write("garbage.textproto", bytes));
  EXPECT_EQ(error.file, (dir_ / "garbage.textproto").string());
  EXPECT_GT(error.line, 0);
  EXPECT_FALSE(error.message.empty());
}

TEST_F(SceneFile, FileLargerThanTheLimitIsRefusedBeforeReading) {
  const auto path = dir_ / "big.textproto";
  std::filesystem::resize_file(write("big.textproto", ""), kMaxSceneFileBytes + 1);
  EXPECT_NE(load_error(path).message.find("limit"), std::string::npos);
}

TEST_F(SceneFile, ErrorsNameTheFile) {
  const auto path = write("bad.textproto", scene_with("bodies { circle { radius: -1 } }\n"));
  const SceneError error = load_error(path);
  EXPECT_EQ(error.to_string(),
            path.string() + ":2:19: bodies[0].circle.radius: must be > 0, got -1");
}

}  // namespace
}  // namespace scene
