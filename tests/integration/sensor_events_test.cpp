// Sensor events to clients (Hello.sensor_events, docs/PROTOCOL.md 3.7): a client that
// asks hears every sensor's begins and ends, tick for tick as the server's world made
// them; a client that did not ask hears none.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <mutex>
#include <vector>

#include "harness.h"
#include "physics_testing/in_process_server.h"
#include "server/game_rules.h"

namespace itest {
namespace {

// Puts a ball in the goal every 30 ticks and takes it away 20 ticks later (a
// begin, then an end), and writes down every sensor event the world makes.
class GoalDropper : public server::GameRules {
 public:
  std::vector<client::SensorEvent> made() {
    std::lock_guard<std::mutex> lock(mutex_);
    return made_;
  }
  void before_step(server::GameWorld& world, const std::vector<server::AppliedInput>&) override {
    if (world.tick() % 30 == 0) {
      phys::BodyDef ball;
      ball.shape = phys::Shape::Circle;
      ball.radius = 0.3;
      ball.position = {11.5, 1.0};  // inside the goal, clear of the ghost balls
      ball_ = world.create(ball);
    }
    if (world.tick() % 30 == 20 && ball_.is_valid()) world.destroy(ball_);
  }
  void after_step(server::GameWorld& world) override {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const phys::SensorEvent& event : world.sensor_events()) {
      made_.push_back({event.kind == phys::SensorEventKind::End, world.tick(),
                       event.sensor.packed(), event.visitor.packed()});
    }
  }

 private:
  phys::BodyId ball_;
  std::mutex mutex_;
  std::vector<client::SensorEvent> made_;
};

TEST(SensorEventsWire, ASubscriberHearsEverySensorEventTheWorldMade) {
  const auto scene = physics_testing::load_scene(PHYSICS_SCENES_DIR "/rules-room.textproto");
  ASSERT_TRUE(scene) << scene.message();
  auto rules = std::make_shared<GoalDropper>();
  server::ServerConfig config = test_config();
  config.rules = rules;
  RunningServer server(config, *scene);

  client::ClientConfig asks = server.client_config("asks");
  asks.sensor_events = true;
  client::ClientConfig silent = server.client_config("silent");
  silent.spectate = true;
  client::Client listener(asks);
  client::Client other(silent);
  ASSERT_TRUE(listener.connect(3s)) << listener.last_error().to_string();
  ASSERT_TRUE(other.connect(3s)) << other.last_error().to_string();
  const std::uint64_t from = listener.welcome().current_tick;
  const auto goal = std::find_if(listener.welcome().bodies.begin(), listener.welcome().bodies.end(),
                                 [](const client::BodyShape& b) { return b.name == "goal"; });
  ASSERT_NE(goal, listener.welcome().bodies.end());
  EXPECT_TRUE(goal->is_sensor);
  const std::uint64_t until = from + 150;  // five drops

  std::vector<client::SensorEvent> heard;
  std::uint64_t last = 0;
  while (last < until) {
    const std::optional<client::Snapshot> snapshot = listener.next_snapshot(3s);
    ASSERT_TRUE(snapshot) << "no snapshot after tick " << last;
    EXPECT_EQ(snapshot->sensor_events_dropped, 0u);
    heard.insert(heard.end(), snapshot->sensor_events.begin(), snapshot->sensor_events.end());
    last = snapshot->tick;
  }
  std::size_t heard_by_other = 0;
  for (int i = 0; i < 30; ++i) {
    if (const auto snapshot = other.next_snapshot(1s))
      heard_by_other += snapshot->sensor_events.size();
  }

  std::vector<client::SensorEvent> made = rules->made();
  std::erase_if(made,
                [&](const client::SensorEvent& e) { return e.tick <= from || e.tick > last; });
  ASSERT_GE(made.size(), 8u) << "ticks " << from << " to " << last;
  EXPECT_TRUE(std::any_of(made.begin(), made.end(), [](const auto& e) { return e.end; }));
  EXPECT_EQ(heard, made);
  for (const client::SensorEvent& event : heard) EXPECT_EQ(event.sensor, goal->body_id);
  EXPECT_EQ(heard_by_other, 0u);
}

}  // namespace
}  // namespace itest
