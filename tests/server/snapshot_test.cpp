// The snapshot encoder: the shared part plus a client's own fields, framed as the
// session writes them, parse as one ServerMessage with the right contents.
#include <gtest/gtest.h>

#include "server/simulation.h"
#include "snapshot_encoder.h"
#include "test_scene.h"
#include "wire/framing.h"
#include "wire/messages.h"

namespace {

// A view's shared part and a client's own part, framed as Session::do_write does,
// parse as one ServerMessage holding both (Protobuf merges concatenated encodings).
TEST(Snapshot, TheSharedPartAndTheClientsOwnFieldsParseAsOneSnapshot) {
  physics::wire::Snapshot shared;
  shared.set_tick(7);
  shared.set_view_hash(0x1234);
  shared.mutable_quantized()->add_id_gaps(3);
  shared.mutable_quantized()->add_dx(-5);
  shared.mutable_quantized()->add_dy(6);
  shared.mutable_quantized()->add_dvx(0);
  shared.mutable_quantized()->add_dvy(1);
  physics::wire::Snapshot own;
  own.set_last_applied_input_tick(6);
  own.set_has_applied_input(true);
  own.add_removed(9);
  const std::string a = shared.SerializeAsString();
  const std::string b = own.SerializeAsString();
  const std::string bytes = server::snapshot_frame_header(a.size() + b.size()) + a + b;
  wire::FrameReader reader;
  reader.feed({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()});
  std::string frame;
  physics::wire::ServerMessage message;
  ASSERT_EQ(reader.next(frame), wire::FrameStatus::Frame);
  ASSERT_TRUE(wire::parse_server_message(frame, message));
  EXPECT_EQ(reader.buffered_bytes(), 0u);
  const auto& snap = message.snapshot();
  EXPECT_EQ(snap.tick(), 7u);
  EXPECT_EQ(snap.view_hash(), 0x1234u);
  EXPECT_EQ(snap.quantized().dx(0), -5);
  EXPECT_EQ(snap.last_applied_input_tick(), 6u);
  EXPECT_TRUE(snap.has_applied_input());
  ASSERT_EQ(snap.removed_size(), 1);
  EXPECT_EQ(snap.removed(0), 9u);
}

TEST(Snapshot, WelcomeDescribesTheWorldAndTheClientsBody) {
  server::Simulation sim(server_test::scene_with_unowned_box());
  const auto body = sim.join(4);
  physics::wire::ViewRequest view;
  view.set_window(9);
  const auto welcome = server::make_welcome(sim, 4, *body, true, view, 64).welcome();
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
  EXPECT_EQ(welcome.view().window(), 9u);
  EXPECT_EQ(welcome.max_players(), 64u);
}

}  // namespace
