// physics-view in a game: sensors drawn translucent over what lies under them,
// kinematic bodies in their own colour, the own body of a viewer that plays ringed
// and labelled; and the game messages its keys queue reach the rules (live and
// predicting), their replies kept for the panel.
#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "harness.h"
#include "live_world.h"
#include "palette.h"
#include "predicted_world.h"
#include "server/game_rules.h"

namespace {

using namespace std::chrono_literals;

constexpr double kScale = 20.0;  // px per metre, passed as --scale
constexpr int kWidth = 640;
constexpr int kHeight = 480;

// No gravity. A static wall with a box sensor over its right half and the space
// above it; a circle sensor over nothing; a kinematic box at rest; the players'
// bodies (circles of radius 1) appear at the origin. The panel covers the top.
scene::SceneDef game_scene() {
  scene::SceneDef scene;
  scene.name = "viewer-game-test";
  scene.world.gravity = {0.0, 0.0};
  scene.spawn_points.push_back({0.0, 0.0});
  scene.player.shape = phys::Shape::Circle;
  scene.player.radius = 1.0;
  auto box = [&](phys::Motion motion, phys::Vec2 at, phys::Vec2 half, bool sensor) {
    phys::BodyDef body;
    body.motion = motion;
    body.shape = phys::Shape::Box;
    body.half_extents = half;
    body.position = at;
    body.is_sensor = sensor;
    scene.bodies.push_back(body);
  };
  box(phys::Motion::Static, {-8.0, -6.0}, {4.0, 1.0}, false);    // wall, y -7 to -5
  box(phys::Motion::Static, {-6.0, -4.0}, {2.0, 3.0}, true);     // sensor, y -7 to -1
  box(phys::Motion::Kinematic, {8.0, -6.0}, {1.5, 0.5}, false);  // kinematic, at rest
  phys::BodyDef ring;
  ring.motion = phys::Motion::Static;
  ring.shape = phys::Shape::Circle;
  ring.radius = 1.5;
  ring.position = {0.0, -6.0};
  ring.is_sensor = true;
  scene.bodies.push_back(ring);
  return scene;
}

struct Picture {
  int width = 0;
  int height = 0;
  std::vector<unsigned char> rgb;

  bool load(const std::string& path) {
    int channels = 0;
    unsigned char* data = stbi_load(path.c_str(), &width, &height, &channels, 3);
    if (data == nullptr) return false;
    rgb.assign(data, data + static_cast<std::size_t>(width) * height * 3);
    stbi_image_free(data);
    return true;
  }
  // The pixel that world point (x, y) lands in, centre (0, 0) (camera.h).
  viewer::Rgb world(double x, double y) const {
    return at(kWidth / 2.0 + x * kScale, kHeight / 2.0 - y * kScale);
  }
  viewer::Rgb at(double px, double py) const {
    const int x = static_cast<int>(std::floor(px));
    const int y = static_cast<int>(std::floor(py));
    if (x < 0 || y < 0 || x >= width || y >= height) return {1, 2, 3};
    const unsigned char* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    return {p[0], p[1], p[2]};
  }
};

std::string describe(viewer::Rgb c) {
  std::ostringstream out;
  out << "(" << int{c.r} << ", " << int{c.g} << ", " << int{c.b} << ")";
  return out.str();
}

// `top` at kSensorAlpha over `under`. The renderer blends in 8-bit integers, so a
// channel may be a unit or two off the exact value.
void expect_blend(viewer::Rgb found, viewer::Rgb top, viewer::Rgb under, const char* where) {
  const double a = viewer::kSensorAlpha / 255.0;
  const auto channel = [&](std::uint8_t t, std::uint8_t u) { return t * a + u * (1.0 - a); };
  EXPECT_NEAR(found.r, channel(top.r, under.r), 2.0) << where << ": " << describe(found);
  EXPECT_NEAR(found.g, channel(top.g, under.g), 2.0) << where << ": " << describe(found);
  EXPECT_NEAR(found.b, channel(top.b, under.b), 2.0) << where << ": " << describe(found);
}

int run_command(const std::string& command, std::string& output) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return -1;
  for (int c = std::fgetc(pipe); c != EOF; c = std::fgetc(pipe))
    output.push_back(static_cast<char>(c));
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class ViewerGame : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = std::make_unique<itest::RunningServer>(itest::test_config(), game_scene());
  }
  void TearDown() override { std::filesystem::remove(path_); }

  Picture screenshot(const std::string& flags) {
    std::string output;
    const int code =
        run_command(std::string(PHYSICS_VIEW_EXE) + " --port " + std::to_string(server_->port()) +
                        " --screenshot " + path_ +
                        " --after-ticks 5 --size 640x480 --scale 20 --center 0,0 " + flags,
                    output);
    EXPECT_EQ(code, 0) << output;
    Picture picture;
    EXPECT_TRUE(picture.load(path_)) << output;
    return picture;
  }

  std::unique_ptr<itest::RunningServer> server_;
  std::string path_ = (std::filesystem::temp_directory_path() /
                       ("physics-view-game-" + std::to_string(::getpid()) + ".png"))
                          .string();
};

TEST_F(ViewerGame, SensorsAreTranslucentAndKinematicBodiesInTheirColour) {
  const Picture picture = screenshot("");
  // The sensor box over the wall, and over the background; the wall beside it.
  expect_blend(picture.world(-5.0, -6.0), viewer::kSensor, viewer::kStatic, "sensor over wall");
  expect_blend(picture.world(-5.0, -3.0), viewer::kSensor, viewer::kBackground,
               "sensor over nothing");
  EXPECT_EQ(picture.world(-10.0, -6.0), viewer::kStatic);
  // The circle sensor, and just outside it.
  expect_blend(picture.world(0.0, -6.0), viewer::kSensor, viewer::kBackground, "circle sensor");
  EXPECT_EQ(picture.world(0.0, -8.0), viewer::kBackground);
  // The kinematic box, and beside it.
  EXPECT_EQ(picture.world(8.0, -6.0), viewer::kKinematic) << describe(picture.world(8.0, -6.0));
  EXPECT_EQ(picture.world(10.5, -6.0), viewer::kBackground);
}

// A spectator has no own body: no ring, no label. A viewer that plays (--play) rings
// its body (just outside its radius) and labels it above.
TEST_F(ViewerGame, APlayingViewerRingsAndLabelsItsOwnBody) {
  const auto count_in = [](const Picture& picture, viewer::Rgb colour, double x0, double x1,
                           double y0, double y1) {
    int n = 0;
    for (double py = y0; py < y1; py += 1.0)
      for (double px = x0; px < x1; px += 1.0) n += picture.at(px, py) == colour;
    return n;
  };
  const double cx = kWidth / 2.0;
  const double cy = kHeight / 2.0;
  // The ring: at 21 to 24 px from the centre (radius 20 px); the label: the 20 px
  // above the body's top.
  const Picture watching = screenshot("");
  EXPECT_EQ(count_in(watching, viewer::kOwnMarker, cx - 25, cx + 25, cy - 25, cy + 25), 0);
  EXPECT_EQ(count_in(watching, viewer::kText, cx - 60, cx + 60, cy - 42, cy - 20), 0);

  const Picture playing = screenshot("--play");
  // At rest (no gravity, a zero input): drawn as still.
  EXPECT_EQ(playing.at(cx, cy), viewer::kSleeping) << describe(playing.at(cx, cy));
  EXPECT_GT(count_in(playing, viewer::kOwnMarker, cx + 20.5, cx + 24.5, cy - 1, cy + 1), 0);
  EXPECT_GT(count_in(playing, viewer::kOwnMarker, cx - 24.5, cx - 20.5, cy - 1, cy + 1), 0);
  EXPECT_GT(count_in(playing, viewer::kText, cx - 60, cx + 60, cy - 42, cy - 20), 10);
}

// Key bindings that do not parse: exit 2, saying which, before any connection.
TEST(ViewerGameFlags, BadKeyBindingsExitWithTwoAndSayWhy) {
  const std::string exe = PHYSICS_VIEW_EXE;
  const std::string keys =
      (std::filesystem::temp_directory_path() / ("keys-" + std::to_string(::getpid()) + ".txt"))
          .string();
  std::ofstream(keys) << "space=jump\nnot a binding\n";
  const std::pair<std::string, std::string> cases[] = {
      {"--key ctrl=jump", "unknown key 'ctrl'"},
      {"--key space=", "no payload"},
      {"--key space", "is not KEY=PAYLOAD"},
      {"--key space=a --key SPACE=b", "bound twice"},
      {"--key x=" + std::string(257, 'p'), "at most 256 bytes; this one has 257"},
      {"--keys " + keys, keys + ":2: "},
      {"--keys /no/such/keys.txt", "--keys"},
      {"--key space=jump --replay " + keys, "excludes"},
      {"--play --replay " + keys, "excludes"},
  };
  for (const auto& [flags, said] : cases) {
    std::string output;
    EXPECT_EQ(run_command(exe + " --port 1 " + flags, output), 2) << flags << ": " << output;
    EXPECT_NE(output.find(said), std::string::npos) << flags << ": " << output;
  }
  std::filesystem::remove(keys);
}

struct Delivered {
  server::ClientId client = 0;
  std::string payload;
};

// Answers each message to its sender, "got <payload>".
class EchoRules : public server::GameRules {
 public:
  void before_step(server::GameWorld& w, const std::vector<server::AppliedInput>&) override {
    for (const server::ClientGameMessage& m : w.messages()) {
      {
        const std::lock_guard lock(mutex_);
        delivered_.push_back({m.client, m.payload});
      }
      w.send(m.client, "got " + m.payload);
    }
  }
  std::vector<Delivered> delivered() const {
    const std::lock_guard lock(mutex_);
    return delivered_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<Delivered> delivered_;
};

class ViewerGameMessages : public ::testing::TestWithParam<bool> {};

// The message a key queues goes out before the next input and reaches the rules;
// their reply is the newest the panel shows. Live (--play) and predicting alike.
TEST_P(ViewerGameMessages, AQueuedMessageReachesTheRulesAndTheReplyIsKept) {
  const bool predict = GetParam();
  server::ServerConfig config = itest::test_config(/*lockstep=*/true);
  auto rules = std::make_shared<EchoRules>();
  config.rules = rules;
  itest::RunningServer server(config, game_scene());
  client::ClientConfig player = server.client_config("viewer");
  player.spectate = false;
  player.view.encoding = client::Encoding::Exact;

  const auto run = [&](auto& world, auto pump) {
    ASSERT_TRUE(world.connect(3s)) << world.error();
    ASSERT_TRUE(world.own_body().has_value());
    EXPECT_TRUE(world.send_game_message("jump"));
    const bool replied = itest::eventually(
        [&] {
          pump();
          return world.game_messages().received_count() > 0;
        },
        10s);
    ASSERT_TRUE(replied) << world.error();
    ASSERT_EQ(rules->delivered().size(), 1u);
    EXPECT_EQ(rules->delivered()[0].payload, "jump");
    EXPECT_EQ(world.game_messages().sent(), 1u);
    ASSERT_EQ(world.game_messages().recent().size(), 1u);
    EXPECT_EQ(world.game_messages().recent().back().payload, "got jump");
    bool shown = false;
    for (const std::string& line : world.panel(client::PlayoutFrame{}, std::nullopt))
      shown = shown || line.find("got jump") != std::string::npos;
    EXPECT_TRUE(shown);
  };
  if (predict) {
    viewer::PredictedWorld world(player);
    run(world, [&] { world.pump(std::chrono::steady_clock::now() + 20ms); });
  } else {
    viewer::LiveWorld world(player);
    run(world, [&] { world.pump(20ms); });
  }
}

INSTANTIATE_TEST_SUITE_P(LiveAndPredicting, ViewerGameMessages, ::testing::Values(false, true),
                         [](const auto& param_info) {
                           return param_info.param ? "Predicting" : "Live";
                         });

// A spectator cannot send one: the source says so, and nothing is queued.
TEST(ViewerGameMessagesSpectator, ASpectatorCannotSend) {
  itest::RunningServer server(itest::test_config(), game_scene());
  client::ClientConfig watcher = server.client_config("viewer");
  watcher.spectate = true;
  viewer::LiveWorld world(watcher);
  ASSERT_TRUE(world.connect(3s)) << world.error();
  EXPECT_FALSE(world.own_body().has_value());
  EXPECT_FALSE(world.send_game_message("jump"));
}

}  // namespace
