// Kinematic bodies over a real socket: the Welcome's BodyShape carries what a client
// needs to draw them and to check the world's state hash (docs/PROTOCOL.md 5.11)
// without the scene file, the client library says how each body moves, and a
// client's own state hash, from shapes and exact snapshots, equals the server's on
// scenes/rules-room.textproto (a moving lift and pusher, filtered ghost balls, a
// ledge of another category, a sensor).
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "client/state_hash.h"
#include "harness.h"

namespace itest {
namespace {

const client::BodyShape* named(const std::vector<client::BodyShape>& shapes, const char* name) {
  const auto it = std::find_if(shapes.begin(), shapes.end(),
                               [&](const client::BodyShape& s) { return s.name == name; });
  return it == shapes.end() ? nullptr : &*it;
}

// The shapes a client knows: Welcome's, plus each snapshot's added, less its removed.
void follow_shapes(std::vector<client::BodyShape>& shapes, const client::Snapshot& s) {
  std::erase_if(shapes, [&](const client::BodyShape& shape) {
    return std::find(s.removed.begin(), s.removed.end(), shape.body_id) != s.removed.end();
  });
  shapes.insert(shapes.end(), s.added.begin(), s.added.end());
}

TEST(KinematicClients, TheWelcomeTellsEachBodysMotionVelocityAndFilter) {
  const auto scene = physics_testing::load_scene(PHYSICS_SCENES_DIR "/rules-room.textproto");
  ASSERT_TRUE(scene) << scene.message();
  RunningServer server(test_config(), *scene);
  client::ClientConfig config = server.client_config("watcher");
  config.spectate = true;
  client::Client watcher(config);
  ASSERT_TRUE(watcher.connect(3s)) << watcher.last_error().to_string();
  const std::vector<client::BodyShape>& shapes = watcher.welcome().bodies;

  const client::BodyShape* lift = named(shapes, "lift");
  ASSERT_NE(lift, nullptr);
  EXPECT_EQ(lift->motion, client::Motion::Kinematic);
  EXPECT_TRUE(lift->is_kinematic);
  EXPECT_EQ(lift->velocity, (client::Vec2{0.5, 0.0}));
  EXPECT_EQ(lift->contact_friction, 0.6);
  const client::BodyShape* ledge = named(shapes, "ghost ledge");
  ASSERT_NE(ledge, nullptr);
  EXPECT_EQ(ledge->motion, client::Motion::Static);
  EXPECT_EQ(ledge->filter, (client::CollisionFilter{2, 0xFFFFFFFFu, 0}));
  const client::BodyShape* ghost = named(shapes, "ghost");
  ASSERT_NE(ghost, nullptr);
  EXPECT_EQ(ghost->motion, client::Motion::Dynamic);
  EXPECT_EQ(ghost->filter, (client::CollisionFilter{1, 0xFFFFFFFDu, -1}));
  const client::BodyShape* goal = named(shapes, "goal");
  ASSERT_NE(goal, nullptr);
  EXPECT_TRUE(goal->is_sensor);
  EXPECT_EQ(goal->filter, client::CollisionFilter{});

  // The lift is in the snapshots, said to be kinematic, and moving.
  std::optional<double> first_x;
  for (int i = 0; i < 10; ++i) {
    const auto s = watcher.next_snapshot(3s);
    ASSERT_TRUE(s.has_value()) << watcher.last_error().to_string();
    const client::BodyState* held = s->find(lift->body_id);
    ASSERT_NE(held, nullptr) << "tick " << s->tick;
    EXPECT_EQ(held->motion, client::Motion::Kinematic);
    if (!first_x) first_x = held->position.x;
    if (i == 9) {
      EXPECT_GT(held->position.x, *first_x);
    }
  }
}

TEST(KinematicClients, AClientsStateHashFromShapesAndExactSnapshotsIsTheServers) {
  const auto scene = physics_testing::load_scene(PHYSICS_SCENES_DIR "/rules-room.textproto");
  ASSERT_TRUE(scene) << scene.message();
  RunningServer server(test_config(), *scene);
  client::ClientConfig config = server.exact_client_config("hasher");
  config.spectate = true;
  client::Client hasher(config);
  ASSERT_TRUE(hasher.connect(3s)) << hasher.last_error().to_string();
  std::vector<client::BodyShape> shapes = hasher.welcome().bodies;
  ASSERT_NE(named(shapes, "lift"), nullptr);

  std::optional<client::Client> player;
  int checked = 0;
  bool saw_added = false;
  for (int i = 0; i < 90; ++i) {
    if (i == 30) {  // a player joins: its body reaches the hasher in Snapshot::added
      player.emplace(server.client_config("player"));
      ASSERT_TRUE(player->connect(3s)) << player->last_error().to_string();
    }
    const auto s = hasher.next_snapshot(3s);
    ASSERT_TRUE(s.has_value()) << hasher.last_error().to_string();
    follow_shapes(shapes, *s);
    if (!s->added.empty()) saw_added = true;
    const std::optional<std::uint64_t> ours = client::state_hash(shapes, s->bodies);
    ASSERT_TRUE(ours.has_value()) << "tick " << s->tick;
    ASSERT_EQ(*ours, s->state_hash) << "tick " << s->tick;
    ++checked;
  }
  EXPECT_EQ(checked, 90);
  EXPECT_TRUE(saw_added);

  // A wrong lift, or none, does not hash as the server's world.
  const auto s = hasher.next_snapshot(3s);
  ASSERT_TRUE(s.has_value());
  follow_shapes(shapes, *s);
  std::vector<client::BodyState> wrong = s->bodies;
  const std::uint64_t lift = named(shapes, "lift")->body_id;
  for (client::BodyState& b : wrong) {
    if (b.body_id == lift) b.position.x += 1e-9;
  }
  EXPECT_NE(client::state_hash(shapes, wrong).value(), s->state_hash);
  std::erase_if(wrong, [&](const client::BodyState& b) { return b.body_id == lift; });
  EXPECT_EQ(client::state_hash(shapes, wrong), std::nullopt);
}

}  // namespace
}  // namespace itest
