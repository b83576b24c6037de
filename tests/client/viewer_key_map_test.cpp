// physics-view's game keys (client/viewer/key_map.h): the key names accepted, the
// bindings' checks (payload size, duplicates), and key map files with the line of
// any error.
#include <SDL_keycode.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "key_map.h"

namespace {

TEST(ViewerKeyMap, NamesTheDocumentedKeysInAnyCase) {
  EXPECT_EQ(viewer::keycode_of("space"), SDLK_SPACE);
  EXPECT_EQ(viewer::keycode_of("SPACE"), SDLK_SPACE);
  EXPECT_EQ(viewer::keycode_of("x"), SDLK_x);
  EXPECT_EQ(viewer::keycode_of("X"), SDLK_x);
  EXPECT_EQ(viewer::keycode_of("7"), SDLK_7);
  EXPECT_EQ(viewer::keycode_of("return"), SDLK_RETURN);
  EXPECT_EQ(viewer::keycode_of("enter"), SDLK_RETURN);
  EXPECT_EQ(viewer::keycode_of("tab"), SDLK_TAB);
  EXPECT_EQ(viewer::keycode_of("backspace"), SDLK_BACKSPACE);
  EXPECT_EQ(viewer::keycode_of("up"), SDLK_UP);
  EXPECT_EQ(viewer::keycode_of("left"), SDLK_LEFT);
  EXPECT_EQ(viewer::keycode_of("f1"), SDLK_F1);
  EXPECT_EQ(viewer::keycode_of("F12"), SDLK_F12);
  for (const char* bad : {"", "f0", "f13", "ff", "ctrl", "xx", "!", "space "}) {
    EXPECT_FALSE(viewer::keycode_of(bad).has_value()) << "'" << bad << "'";
  }
}

TEST(ViewerKeyMap, ABindingIsKeyEqualsPayload) {
  std::string error;
  const auto jump = viewer::parse_key_binding("Space=jump", error);
  ASSERT_TRUE(jump.has_value()) << error;
  EXPECT_EQ(jump->keycode, SDLK_SPACE);
  EXPECT_EQ(jump->name, "space");
  EXPECT_EQ(jump->payload, "jump");
  // Everything after the first '=' is the payload, '=' and spaces included.
  const auto say = viewer::parse_key_binding("t=say a=b", error);
  ASSERT_TRUE(say.has_value()) << error;
  EXPECT_EQ(say->payload, "say a=b");
  const auto longest = viewer::parse_key_binding("x=" + std::string(256, 'p'), error);
  EXPECT_TRUE(longest.has_value()) << error;
}

TEST(ViewerKeyMap, RefusesBadBindingsSayingWhy) {
  std::string error;
  EXPECT_FALSE(viewer::parse_key_binding("space", error));
  EXPECT_NE(error.find("KEY=PAYLOAD"), std::string::npos) << error;
  EXPECT_FALSE(viewer::parse_key_binding("ctrl=jump", error));
  EXPECT_NE(error.find("unknown key 'ctrl'"), std::string::npos) << error;
  EXPECT_FALSE(viewer::parse_key_binding("space=", error));
  EXPECT_NE(error.find("no payload"), std::string::npos) << error;
  EXPECT_FALSE(viewer::parse_key_binding("x=" + std::string(257, 'p'), error));
  EXPECT_NE(error.find("at most 256 bytes; this one has 257"), std::string::npos) << error;

  std::vector<viewer::KeyBinding> map;
  EXPECT_TRUE(viewer::add_binding(map, *viewer::parse_key_binding("x=shoot", error), error));
  EXPECT_FALSE(viewer::add_binding(map, *viewer::parse_key_binding("X=dash", error), error));
  EXPECT_NE(error.find("bound twice"), std::string::npos) << error;
  ASSERT_EQ(map.size(), 1u);
  ASSERT_NE(viewer::find_binding(map, SDLK_x), nullptr);
  EXPECT_EQ(viewer::find_binding(map, SDLK_x)->payload, "shoot");
  EXPECT_EQ(viewer::find_binding(map, SDLK_y), nullptr);
}

class KeyMapFile : public ::testing::Test {
 protected:
  std::string write(const std::string& text) {
    std::ofstream(path_, std::ios::binary) << text;
    return path_;
  }
  void TearDown() override { std::filesystem::remove(path_); }
  std::string path_ = (std::filesystem::temp_directory_path() /
                       ("physics-view-keys-" + std::to_string(::getpid()) + ".txt"))
                          .string();
};

TEST_F(KeyMapFile, ReadsOneBindingALineSkippingCommentsAndBlanks) {
  std::vector<viewer::KeyBinding> map;
  std::string error;
  ASSERT_TRUE(viewer::read_key_map(write("# goal rush\nspace=jump\r\n\nx=shoot\n"), map, error))
      << error;
  ASSERT_EQ(map.size(), 2u);
  EXPECT_EQ(map[0].keycode, SDLK_SPACE);
  EXPECT_EQ(map[0].payload, "jump");  // the CRLF's CR is not part of it
  EXPECT_EQ(map[1].payload, "shoot");
}

TEST_F(KeyMapFile, NamesTheLineThatDoesNotParse) {
  std::vector<viewer::KeyBinding> map;
  std::string error;
  EXPECT_FALSE(viewer::read_key_map(write("space=jump\n# fine\nwhat\n"), map, error));
  EXPECT_NE(error.find(":3: "), std::string::npos) << error;
  EXPECT_FALSE(viewer::read_key_map(write("space=jump\nspace=dash\n"), map, error));
  EXPECT_NE(error.find("bound twice"), std::string::npos) << error;
  EXPECT_FALSE(viewer::read_key_map("/no/such/keys.txt", map, error));
  EXPECT_NE(error.find("cannot read"), std::string::npos) << error;
  // Bytes that are not text: refused as a bad line, not a crash.
  map.clear();
  EXPECT_FALSE(viewer::read_key_map(write(std::string("\xff\xfe\x00=\x01", 5)), map, error));
}

}  // namespace
