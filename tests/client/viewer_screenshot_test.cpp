// physics-view --screenshot against a real server: the picture holds each body's
// colour where the snapshot of the tick it shows puts the body (through the
// viewer's world-to-pixel mapping, client/viewer/camera.h), and the background
// where there is none.
#define STB_IMAGE_IMPLEMENTATION
#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "client/client_recording.h"
#include "harness.h"
#include "palette.h"
#include "recording/recording_file.h"

namespace {

using namespace std::chrono_literals;

constexpr double kScale = 20.0;  // px per metre, passed as --scale
constexpr int kWidth = 640;
constexpr int kHeight = 480;
constexpr double kRadius = 1.0;

// No gravity: three circles glide at constant velocity (awake: drawn as dynamic),
// two lie still (drawn as sleeping), and a static slab lies below them all. The
// panel covers the top of the picture; every body is below it.
scene::SceneDef viewer_scene() {
  scene::SceneDef scene;
  scene.name = "viewer-test";
  scene.world.gravity = {0.0, 0.0};
  scene.spawn_points.push_back({0.0, 50.0});
  auto circle = [&](phys::Vec2 at, phys::Vec2 velocity) {
    phys::BodyDef body;
    body.shape = phys::Shape::Circle;
    body.radius = kRadius;
    body.position = at;
    body.velocity = velocity;
    scene.bodies.push_back(body);
  };
  circle({-8.0, 0.0}, {0.5, 0.0});
  circle({0.0, 0.0}, {0.5, 0.0});
  circle({8.0, -2.0}, {-0.3, 0.2});
  circle({-6.0, -5.0}, {0.0, 0.0});
  circle({4.0, -5.0}, {0.0, 0.0});
  phys::BodyDef slab;
  slab.motion = phys::Motion::Static;
  slab.shape = phys::Shape::Box;
  slab.half_extents = {14.0, 0.5};
  slab.position = {0.0, -9.0};
  scene.bodies.push_back(slab);
  return scene;
}

struct CommandRun {
  int exit_code = -1;
  std::string output;
};

CommandRun run_command(const std::string& command) {
  CommandRun run;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return run;
  for (int c = std::fgetc(pipe); c != EOF; c = std::fgetc(pipe))
    run.output.push_back(static_cast<char>(c));
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

// The tick from the viewer's "screenshot FILE tick T size ..." line; 0 if absent.
std::uint64_t shown_tick(const std::string& output) {
  const auto at = output.find(" tick ");
  if (output.rfind("screenshot ", 0) != 0 || at == std::string::npos) return 0;
  return std::stoull(output.substr(at + 6));
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

// A spectator taking every snapshot (full encoding: every tick, every body), on its
// own thread while the viewer runs, so that the snapshot of the tick the picture
// shows is at hand.
class Recorder {
 public:
  explicit Recorder(client::ClientConfig config) : client_(std::move(config)) {}
  ~Recorder() { stop(); }
  bool connect() { return client_.connect(3s); }
  void start() {
    thread_ = std::thread([this] {
      while (!stopping_) {
        auto snapshot = client_.next_snapshot(50ms);
        if (!snapshot) continue;
        std::lock_guard<std::mutex> lock(mutex_);
        if (seen_.size() < 100000) seen_.emplace(snapshot->tick, std::move(*snapshot));
      }
    });
  }
  void stop() {
    stopping_ = true;
    if (thread_.joinable()) thread_.join();
  }
  std::optional<client::Snapshot> at(std::uint64_t tick) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = seen_.find(tick);
    if (it == seen_.end()) return std::nullopt;
    return it->second;
  }
  const client::Welcome& welcome() const { return client_.welcome(); }

 private:
  client::Client client_;
  std::thread thread_;
  std::atomic<bool> stopping_{false};
  std::mutex mutex_;
  std::map<std::uint64_t, client::Snapshot> seen_;
};

class ViewerScreenshot : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = std::make_unique<itest::RunningServer>(itest::test_config(), viewer_scene());
    client::ClientConfig config = server_->client_config("recorder");
    config.spectate = true;
    config.view.encoding = client::Encoding::Full;
    // The widest window the server allows by default: a recorder slowed by a busy
    // machine falls a second behind before the server skips a tick for it.
    config.view.window = 64;
    recorder_ = std::make_unique<Recorder>(config);
    ASSERT_TRUE(recorder_->connect());
    recorder_->start();
    directory_ = std::filesystem::temp_directory_path() /
                 ("physics-view-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override {
    recorder_.reset();
    std::filesystem::remove_all(directory_);
  }

  // Runs the viewer; returns the tick its picture shows (0 on failure).
  std::uint64_t screenshot(const std::string& name, const std::string& flags, Picture& picture) {
    const std::string path = (directory_ / name).string();
    const CommandRun run =
        run_command(std::string(PHYSICS_VIEW_EXE) + " --port " + std::to_string(server_->port()) +
                    " --screenshot " + path + " --after-ticks 30 --size 640x480 " + flags);
    EXPECT_EQ(run.exit_code, 0) << run.output;
    EXPECT_TRUE(picture.load(path)) << "no picture at " << path << ": " << run.output;
    EXPECT_EQ(picture.width, kWidth);
    EXPECT_EQ(picture.height, kHeight);
    const std::uint64_t tick = shown_tick(run.output);
    EXPECT_GT(tick, 0u) << run.output;
    return tick;
  }

  // The body states of the snapshot of `tick`, by id, from the recorder.
  std::map<std::uint64_t, client::BodyState> bodies_at(std::uint64_t tick) {
    std::optional<client::Snapshot> snapshot;
    itest::eventually([&] { return (snapshot = recorder_->at(tick)).has_value(); });
    EXPECT_TRUE(snapshot.has_value()) << "the recorder saw no snapshot of tick " << tick;
    std::map<std::uint64_t, client::BodyState> out;
    if (snapshot)
      for (const auto& body : snapshot->bodies) out[body.body_id] = body;
    return out;
  }

  std::unique_ptr<itest::RunningServer> server_;
  std::unique_ptr<Recorder> recorder_;
  std::filesystem::path directory_;
};

// camera.h: px = width / 2 + (x - cx) * scale, py = height / 2 - (y - cy) * scale.
struct Mapping {
  client::Vec2 center;
  double px(double x) const { return kWidth / 2.0 + (x - center.x) * kScale; }
  double py(double y) const { return kHeight / 2.0 - (y - center.y) * kScale; }
};

// The body's colour fills its disc (centre and four points at 60% of the radius),
// and the background lies just outside it on the side facing away from the others.
void expect_disc(const Picture& picture, const Mapping& map, const client::BodyState& body,
                 viewer::Rgb colour) {
  const double r = 0.6 * kRadius;
  const client::Vec2 p = body.position;
  const client::Vec2 inside[] = {{0, 0}, {r, 0}, {-r, 0}, {0, r}, {0, -r}};
  for (const client::Vec2& d : inside) {
    const viewer::Rgb found = picture.at(map.px(p.x + d.x), map.py(p.y + d.y));
    EXPECT_EQ(found, colour) << "body " << body.body_id << " at (" << p.x << ", " << p.y << ") + ("
                             << d.x << ", " << d.y << "): found " << describe(found) << ", want "
                             << describe(colour);
  }
  const viewer::Rgb outside = picture.at(map.px(p.x), map.py(p.y + 1.5 * kRadius));
  EXPECT_EQ(outside, viewer::kBackground)
      << "above body " << body.body_id << ": found " << describe(outside);
}

TEST_F(ViewerScreenshot, DrawsEachBodyWhereTheSnapshotPutsIt) {
  Picture picture;
  const std::uint64_t tick = screenshot("world.png", "--scale 20 --center 0,0", picture);
  ASSERT_GT(tick, recorder_->welcome().current_tick);
  const auto bodies = bodies_at(tick);
  ASSERT_EQ(bodies.size(), 5u);
  const Mapping map{{0.0, 0.0}};
  int moving = 0;
  int resting = 0;
  for (const auto& [id, body] : bodies) {
    const bool still = body.velocity.x == 0.0 && body.velocity.y == 0.0;
    expect_disc(picture, map, body, still ? viewer::kSleeping : viewer::kDynamic);
    (still ? resting : moving) += 1;
  }
  EXPECT_EQ(moving, 3);
  EXPECT_EQ(resting, 2);
  // The moving circles left their starting points 30 ticks and more ago (0.25 m at
  // least): the picture is of the tick it names, not of the Welcome.
  EXPECT_GE(bodies.begin()->second.position.x, -8.0 + 0.5 * 30.0 / 60.0 - 1e-9);
  // The static slab, and empty places.
  EXPECT_EQ(picture.at(map.px(-10.0), map.py(-9.0)), viewer::kStatic);
  EXPECT_EQ(picture.at(map.px(12.0), map.py(-9.0)), viewer::kStatic);
  EXPECT_EQ(picture.at(map.px(12.0), map.py(-5.0)), viewer::kBackground);
  EXPECT_EQ(picture.at(map.px(-12.0), map.py(2.0)), viewer::kBackground);
  EXPECT_EQ(picture.at(map.px(0.0), map.py(-7.0)), viewer::kBackground);
  // The slab's top edge (y = -8.5, pixel row 410) is outlined: a box's outline is one
  // pixel inside it, in kBoxOutline, and its fill starts just below.
  const double top = map.py(-8.5);
  const bool outlined = picture.at(map.px(0.0), top) == viewer::kBoxOutline ||
                        picture.at(map.px(0.0), top + 1.0) == viewer::kBoxOutline;
  EXPECT_TRUE(outlined) << "found " << describe(picture.at(map.px(0.0), top)) << " and "
                        << describe(picture.at(map.px(0.0), top + 1.0));
  EXPECT_EQ(picture.at(map.px(0.0), top + 3.0), viewer::kStatic);
}

TEST_F(ViewerScreenshot, TheFollowedBodyIsAtTheCentreInItsOwnColour) {
  const std::uint64_t followed = recorder_->welcome().bodies.front().body_id;
  ASSERT_FALSE(recorder_->welcome().bodies.front().is_static);
  Picture picture;
  const std::uint64_t tick =
      screenshot("follow.png", "--scale 20 --follow " + std::to_string(followed), picture);
  const auto bodies = bodies_at(tick);
  ASSERT_EQ(bodies.count(followed), 1u);
  const Mapping map{bodies.at(followed).position};
  expect_disc(picture, map, bodies.at(followed), viewer::kFollowed);
  for (const auto& [id, body] : bodies) {
    if (id == followed) continue;
    if (std::abs(map.px(body.position.x) - kWidth / 2.0) > kWidth / 2.0 - 30.0) continue;
    const bool still = body.velocity.x == 0.0 && body.velocity.y == 0.0;
    expect_disc(picture, map, body, still ? viewer::kSleeping : viewer::kDynamic);
  }
}

TEST_F(ViewerScreenshot, AClientRecordingPlaysBackAsItWasSeen) {
  const std::string path = (directory_ / "seen.rec").string();
  client::ClientConfig config = server_->client_config("taped");
  config.spectate = true;
  config.view.encoding = client::Encoding::Exact;
  config.view.state_hash = true;
  config.record_path = path;
  std::vector<client::Snapshot> live;
  {
    client::Client taped(config);
    ASSERT_TRUE(taped.connect(3s)) << taped.last_error().to_string();
    while (live.size() < 40) {
      auto snapshot = taped.next_snapshot(3s);
      ASSERT_TRUE(snapshot.has_value()) << taped.last_error().to_string();
      live.push_back(*snapshot);
    }
    taped.disconnect();
  }
  // Read back, the recording decodes to what the client was given live, bit for bit.
  auto read = client::read_client_recording(path);
  ASSERT_TRUE(std::holds_alternative<client::ClientRecording>(read)) << std::get<std::string>(read);
  const client::ClientRecording& recording = std::get<client::ClientRecording>(read);
  EXPECT_TRUE(recording.welcome.spectator);
  ASSERT_GE(recording.snapshots.size(), live.size());
  for (std::size_t i = 0; i < live.size(); ++i) {
    EXPECT_EQ(recording.snapshots[i].snapshot.tick, live[i].tick);
    EXPECT_EQ(recording.snapshots[i].snapshot.state_hash, live[i].state_hash);
    EXPECT_EQ(recording.snapshots[i].snapshot.bodies, live[i].bodies) << "tick " << live[i].tick;
    if (i > 0) {
      EXPECT_GE(recording.snapshots[i].arrival, recording.snapshots[i - 1].arrival);
    }
  }

  // The viewer plays it: its picture of a tick holds the bodies where the recording has them.
  Picture picture;
  const std::string replay_flags = "--replay " + path + " --scale 20 --center 0,0";
  const CommandRun run =
      run_command(std::string(PHYSICS_VIEW_EXE) + " " + replay_flags + " --screenshot " +
                  (directory_ / "replay.png").string() + " --after-ticks 20 --size 640x480");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  ASSERT_TRUE(picture.load((directory_ / "replay.png").string()));
  const std::uint64_t tick = shown_tick(run.output);
  ASSERT_GE(tick, recording.welcome.current_tick + 20);
  const client::Snapshot* shown = nullptr;
  for (const auto& recorded : recording.snapshots)
    if (recorded.snapshot.tick == tick) shown = &recorded.snapshot;
  ASSERT_NE(shown, nullptr) << "no recorded snapshot of tick " << tick;
  ASSERT_EQ(shown->bodies.size(), 5u);
  const Mapping map{{0.0, 0.0}};
  for (const client::BodyState& body : shown->bodies) {
    const bool still = body.velocity.x == 0.0 && body.velocity.y == 0.0;
    expect_disc(picture, map, body, still ? viewer::kSleeping : viewer::kDynamic);
  }

  // A recording cut inside its last record is refused, naming the offset.
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ASSERT_GT(bytes.size(), 100u);
  const std::string cut = (directory_ / "cut.rec").string();
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() - 2);
  auto refused = client::read_client_recording(cut);
  ASSERT_TRUE(std::holds_alternative<std::string>(refused));
  EXPECT_NE(std::get<std::string>(refused).find("offset"), std::string::npos)
      << std::get<std::string>(refused);
  const CommandRun failed = run_command(std::string(PHYSICS_VIEW_EXE) + " --replay " + cut +
                                        " --screenshot " + (directory_ / "cut.png").string());
  EXPECT_EQ(failed.exit_code, 1) << failed.output;
  EXPECT_NE(failed.output.find("offset"), std::string::npos) << failed.output;

  // A server recording is not a client's: refused with what it is.
  physics::recording::Header header;
  header.mutable_server()->set_tick_rate(60.0);
  auto server_file = client::read_client_recording_bytes(recording::encode_recording(header, {}));
  ASSERT_TRUE(std::holds_alternative<std::string>(server_file));
  EXPECT_NE(std::get<std::string>(server_file).find("not a client recording"), std::string::npos);
  // So is a file that is not a recording at all.
  auto garbage = client::read_client_recording_bytes("not a recording at all");
  ASSERT_TRUE(std::holds_alternative<std::string>(garbage));
  EXPECT_NE(std::get<std::string>(garbage).find("offset 0"), std::string::npos)
      << std::get<std::string>(garbage);
}

TEST_F(ViewerScreenshot, BadFlagsExitWithTwoAndSayWhy) {
  const std::string exe = PHYSICS_VIEW_EXE;
  for (const std::string& flags :
       {std::string("--size 10x10"), std::string("--size big"), std::string("--scale nan"),
        std::string("--scale -1"), std::string("--center 1"), std::string("--after-ticks 5"),
        std::string("--screenshot out.jpg"), std::string("--encoding fast"),
        std::string("--speed 2"), std::string("--replay /no/such/file.rec"),
        std::string("--no-such-flag")}) {
    const CommandRun run = run_command(exe + " " + flags);
    EXPECT_EQ(run.exit_code, 2) << flags << ": " << run.output;
    EXPECT_FALSE(run.output.empty()) << flags;
  }
  // A server that is not there: exit 1, with the reason.
  const CommandRun run =
      run_command(exe + " --port 1 --screenshot " + (directory_ / "none.png").string() +
                  " --connect-timeout-ms 2000");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("cannot join"), std::string::npos) << run.output;
}

}  // namespace
