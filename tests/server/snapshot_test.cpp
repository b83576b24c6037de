// The snapshot encoder: the shared part plus a client's own fields, framed as the
// session writes them, parse as one ServerMessage with the right contents.
#include <gtest/gtest.h>

#include <cstdio>

#include "server/simulation.h"
#include "snapshot_encoder.h"
#include "test_scene.h"
#include "wire/framing.h"
#include "wire/messages.h"

namespace {

// Assembles a frame exactly as Session::do_write does.
physics::wire::ServerMessage frame_and_parse(const server::EncodedSnapshot& snapshot,
                                             const std::string& carried, std::uint64_t last_applied,
                                             bool has_applied) {
  const std::string tail = carried + server::encode_client_fields(last_applied, has_applied);
  const std::string bytes =
      server::snapshot_frame_header(snapshot.shared.size() + tail.size()) + snapshot.shared + tail;
  wire::FrameReader reader;
  reader.feed({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()});
  std::string frame;
  physics::wire::ServerMessage message;
  EXPECT_EQ(reader.next(frame), wire::FrameStatus::Frame);
  EXPECT_TRUE(wire::parse_server_message(frame, message));
  EXPECT_EQ(reader.buffered_bytes(), 0u);
  return message;
}

TEST(Snapshot, CarriesTickHashEveryDynamicBodyAndTheClientsOwnFields) {
  server::Simulation sim(server_test::scene_with_unowned_box());
  const auto a = sim.join(1);
  const auto b = sim.join(2);
  sim.submit_input(1, 1, {5.0, 0.0});
  sim.step_tick();
  const auto encoded = server::encode_snapshot(sim.world(), 1, sim.take_changes());
  EXPECT_EQ(encoded->state_hash, sim.world().state_hash());

  const auto for_1 = frame_and_parse(*encoded, {}, sim.inputs_of(1)->last_applied_tick(),
                                     sim.inputs_of(1)->has_applied());
  ASSERT_TRUE(for_1.has_snapshot());
  const auto& snap = for_1.snapshot();
  EXPECT_EQ(snap.tick(), 1u);
  EXPECT_EQ(snap.state_hash(), sim.world().state_hash());
  EXPECT_EQ(snap.last_applied_input_tick(), 1u);
  EXPECT_TRUE(snap.has_applied_input());
  // The box and both balls, ascending ids, with their exact state.
  const auto bodies = sim.world().bodies();
  ASSERT_EQ(snap.bodies_size(), 3);
  for (int i = 0; i < snap.bodies_size(); ++i) {
    const auto& state = snap.bodies(i);
    const phys::BodyState truth = *sim.world().body(phys::BodyId::from_packed(state.body_id()));
    EXPECT_EQ(state.x(), truth.position.x);
    EXPECT_EQ(state.y(), truth.position.y);
    EXPECT_EQ(state.vx(), truth.velocity.x);
    EXPECT_EQ(state.vy(), truth.velocity.y);
    if (i > 0) {
      EXPECT_LT(phys::BodyId::from_packed(snap.bodies(i - 1).body_id()).index,
                phys::BodyId::from_packed(state.body_id()).index);
    }
  }
  // Both players were added since the last snapshot.
  ASSERT_EQ(snap.added_size(), 2);
  EXPECT_EQ(snap.added(0).body_id(), a->packed());
  EXPECT_EQ(snap.added(1).body_id(), b->packed());
  EXPECT_EQ(snap.added(0).shape(), physics::wire::SHAPE_CIRCLE);
  EXPECT_EQ(snap.added(0).radius(), 0.5);

  // The same shared bytes for client 2, with client 2's own fields.
  const auto for_2 = frame_and_parse(*encoded, {}, 0, false);
  EXPECT_EQ(for_2.snapshot().state_hash(), snap.state_hash());
  EXPECT_FALSE(for_2.snapshot().has_applied_input());
  EXPECT_EQ(for_2.snapshot().last_applied_input_tick(), 0u);
}

TEST(Snapshot, StaticBodiesAreNotSentEachTick) {
  scene::SceneDef scene = server_test::free_space_scene();
  phys::BodyDef wall;
  wall.motion = phys::Motion::Static;
  wall.position = {0.0, -50.0};
  wall.half_extents = {5.0, 1.0};
  scene.bodies.push_back(wall);
  server::Simulation sim(scene);
  sim.step_tick();
  const auto encoded = server::encode_snapshot(sim.world(), 1, sim.take_changes());
  EXPECT_EQ(frame_and_parse(*encoded, {}, 0, false).snapshot().bodies_size(), 0);
}

TEST(Snapshot, ChangesOfADroppedSnapshotAreCarriedIntoTheNext) {
  server::Simulation sim(server_test::free_space_scene());
  const auto a = sim.join(1);
  sim.step_tick();
  const auto first = server::encode_snapshot(sim.world(), 1, sim.take_changes());
  const auto b = sim.join(2);
  sim.leave(1);
  sim.step_tick();
  const auto second = server::encode_snapshot(sim.world(), 2, sim.take_changes());
  // A slow client never got `first`: its changes ride along with `second`.
  const auto message = frame_and_parse(*second, first->changes, 0, false);
  const auto& snap = message.snapshot();
  EXPECT_EQ(snap.tick(), 2u);
  ASSERT_EQ(snap.added_size(), 2);  // b (this tick) and a (carried)
  EXPECT_EQ(snap.added(0).body_id(), b->packed());
  EXPECT_EQ(snap.added(1).body_id(), a->packed());
  ASSERT_EQ(snap.removed_size(), 1);
  EXPECT_EQ(snap.removed(0), a->packed());
}

TEST(Snapshot, WelcomeDescribesTheWorldAndTheClientsBody) {
  server::Simulation sim(server_test::scene_with_unowned_box());
  const auto body = sim.join(4);
  const auto welcome = server::make_welcome(sim, 4, *body, true).welcome();
  EXPECT_EQ(welcome.protocol_version(), wire::kProtocolVersion);
  EXPECT_EQ(welcome.client_id(), 4u);
  EXPECT_EQ(welcome.body_id(), body->packed());
  EXPECT_EQ(welcome.tick_rate(), 60.0);
  EXPECT_EQ(welcome.current_tick(), 0u);
  EXPECT_EQ(welcome.bodies_size(), 2);
  EXPECT_EQ(welcome.max_acceleration(), 50.0);
  EXPECT_TRUE(welcome.lockstep());
  EXPECT_EQ(welcome.max_ticks_ahead(), 120u);
  EXPECT_EQ(welcome.scene_name(), "free space");
  EXPECT_EQ(welcome.bodies(0).shape(), physics::wire::SHAPE_BOX);
  EXPECT_EQ(welcome.bodies(0).half_extents().x(), 0.5);
}

}  // namespace

namespace {

TEST(Snapshot, CostPerDynamicBodyIsAFewDozenBytes) {
  // 100 free balls: the snapshot grows by one BodyState (id + 4 doubles) per body.
  scene::SceneDef scene = server_test::free_space_scene();
  for (int i = 0; i < 100; ++i) {
    phys::BodyDef ball = scene.player;
    ball.position = {static_cast<double>(i) * 2.0, 50.0};
    ball.velocity = {1.0 + i, -2.5};
    scene.bodies.push_back(ball);
  }
  server::Simulation sim(scene);
  sim.step_tick();
  const auto encoded = server::encode_snapshot(sim.world(), 1, sim.take_changes());
  const double per_body = static_cast<double>(encoded->shared.size()) / 100.0;
  const auto welcome = server::make_welcome(sim, 1, phys::BodyId{}, false);
  const double per_shape = static_cast<double>(welcome.ByteSizeLong()) / 100.0;
  std::printf("snapshot: %.1f bytes per dynamic body; welcome: %.1f bytes per body\n", per_body,
              per_shape);
  EXPECT_LE(per_body, 48.0);  // 4 doubles (36 bytes) + id + tags
  EXPECT_LE(per_shape, 100.0);
}

}  // namespace
