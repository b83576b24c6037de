// Bad values in messages that parse: a Hello with another protocol version, a wrong
// token or view settings out of range (refused, fatal); inputs that are not finite,
// for a tick too far ahead, or huge (refused or clamped, the session stays, and no
// body but the sender's own moves).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "bad_input_fixture.h"
#include "test_scenes.h"
#include "wire/messages.h"

namespace itest {
namespace {

namespace pb = physics::wire;

// A newer client through the client library, an older one (a raw Hello of version
// 1): both refused, fatal, with a message naming both versions, and closed.
TEST_F(BadInput, WrongProtocolVersionIsRefusedNamingBothVersions) {
  start();
  client::ClientConfig config = server_->client_config("from-the-future");
  config.protocol_version = 99;
  client::Client client(config);
  EXPECT_FALSE(client.connect(3s));
  EXPECT_EQ(client.state(), client::ConnectionState::Refused);
  ASSERT_TRUE(client.last_error().server.has_value()) << client.last_error().to_string();
  const client::ServerError& error = *client.last_error().server;
  EXPECT_EQ(error.code, client::ErrorCode::ProtocolVersion);
  EXPECT_TRUE(error.fatal);
  EXPECT_NE(error.message.find("99"), std::string::npos) << error.message;
  EXPECT_NE(error.message.find(std::to_string(client::kProtocolVersion)), std::string::npos)
      << error.message;

  RawPeer old(server_->port());
  pb::ClientMessage hello = hello_message("from-the-past");
  hello.mutable_hello()->set_protocol_version(1);
  ASSERT_TRUE(old.send(hello));
  const auto raw_error = old.receive_error(3s);
  ASSERT_TRUE(raw_error.has_value());
  EXPECT_EQ(raw_error->code(), pb::ERROR_PROTOCOL_VERSION);
  EXPECT_TRUE(raw_error->fatal());
  EXPECT_NE(raw_error->message().find("version 1"), std::string::npos) << raw_error->message();
  EXPECT_NE(raw_error->message().find(std::to_string(client::kProtocolVersion)), std::string::npos)
      << raw_error->message();
  EXPECT_TRUE(old.wait_closed(3s));
  EXPECT_TRUE(eventually(
      [&] { return dropped(server_->stats(), server::DropReason::ProtocolVersion) == 2; }));
}

TEST_F(BadInput, WrongTokenIsRefused) {
  server::ServerConfig config = test_config();
  config.token = "sesame";
  start(config);
  // No token, a wrong one, and one a letter off.
  for (const std::string token : {"wrong", "", "sesamf"}) {
    client::ClientConfig intruder = server_->client_config("intruder");
    intruder.token = token;
    client::Client client(intruder);
    EXPECT_FALSE(client.connect(3s));
    EXPECT_EQ(client.state(), client::ConnectionState::Refused);
    ASSERT_TRUE(client.last_error().server.has_value()) << client.last_error().to_string();
    EXPECT_EQ(client.last_error().server->code, client::ErrorCode::BadToken);
    EXPECT_TRUE(client.last_error().server->fatal);
  }
  EXPECT_TRUE(
      eventually([&] { return dropped(server_->stats(), server::DropReason::BadToken) == 3; }));
  // The right token still joins after the refusals.
  client::ClientConfig right = server_->client_config("right");
  ASSERT_EQ(right.token, "sesame");
  client::Client player(right);
  EXPECT_TRUE(player.connect(3s)) << player.last_error().to_string();
}

TEST_F(BadInput, NanAndInfiniteAccelerationAreRefusedAndTheSessionStays) {
  start();
  client::Client player(server_->client_config("nan"));
  ASSERT_TRUE(player.connect(3s));
  const std::uint64_t tick = player.welcome().current_tick + 2;
  ASSERT_TRUE(player.send_input(tick, std::nan(""), 0.0));
  ASSERT_TRUE(player.send_input(tick + 1, 0.0, std::numeric_limits<double>::infinity()));
  for (int i = 0; i < 2; ++i) {
    auto error = player.next_error(3s);
    ASSERT_TRUE(error.has_value()) << player.last_error().to_string();
    EXPECT_EQ(error->code, client::ErrorCode::InvalidInput);
    EXPECT_FALSE(error->fatal);
  }
  EXPECT_EQ(player.state(), client::ConnectionState::Connected);
  EXPECT_EQ(server_->stats().invalid_inputs, 2u);
  // Snapshots keep coming, the refused inputs were never applied, and the body is finite.
  auto later =
      player.wait_for_snapshot(3s, [&](const client::Snapshot& s) { return s.tick > tick + 2; });
  ASSERT_TRUE(later.has_value());
  EXPECT_FALSE(later->has_applied_input);
  ASSERT_TRUE(later->own.has_value());
  EXPECT_TRUE(std::isfinite(later->own->position.x) && std::isfinite(later->own->position.y));
  // A good input afterwards is applied.
  const std::uint64_t good = later->tick + 2;
  ASSERT_TRUE(player.send_input(good, 1.0, 0.0));
  EXPECT_TRUE(player
                  .wait_for_snapshot(3s,
                                     [&](const client::Snapshot& s) {
                                       return s.has_applied_input &&
                                              s.last_applied_input_tick >= good;
                                     })
                  .has_value());
  EXPECT_EQ(server_->stats().dropped_total(), 0u);  // nobody was dropped for them
}

TEST_F(BadInput, InputForAFarFutureTickIsRefused) {
  start();
  client::Client player(server_->client_config("far-future"));
  ASSERT_TRUE(player.connect(3s));
  const std::uint64_t now = player.welcome().current_tick;
  const std::uint64_t ahead = player.welcome().max_ticks_ahead;
  ASSERT_GT(ahead, 0u);
  ASSERT_TRUE(player.send_input(now + ahead + 1000, 40.0, 0.0));
  ASSERT_TRUE(player.send_input(std::numeric_limits<std::uint64_t>::max(), 40.0, 0.0));
  for (int i = 0; i < 2; ++i) {
    auto error = player.next_error(3s);
    ASSERT_TRUE(error.has_value()) << player.last_error().to_string();
    EXPECT_EQ(error->code, client::ErrorCode::TickTooFarAhead);
    EXPECT_FALSE(error->fatal);
  }
  EXPECT_EQ(player.state(), client::ConnectionState::Connected);
  EXPECT_EQ(server_->stats().far_future_inputs, 2u);
  auto later =
      player.wait_for_snapshot(3s, [&](const client::Snapshot& s) { return s.tick > now + 3; });
  ASSERT_TRUE(later.has_value());
  EXPECT_FALSE(later->has_applied_input);           // neither input was filed for later
  EXPECT_EQ(server_->stats().dropped_total(), 0u);  // nobody was dropped for them
}

// No message a client can send moves any body but its own: in a scene without
// gravity every other body stays exactly where it was, however hostile the inputs.
TEST_F(BadInput, NoMessageMovesAnyBodyButTheSendersOwn) {
  scene::SceneDef scene = crowd_scene(20);
  start(test_config(), scene);
  auto before = bystander_->newest_snapshot(3s);
  ASSERT_TRUE(before.has_value());

  client::Client attacker(server_->client_config("attacker"));
  ASSERT_TRUE(attacker.connect(3s));
  const std::uint64_t now = attacker.welcome().current_tick;
  const double huge = std::numeric_limits<double>::max();
  attacker.send_input(now + 1, huge, -huge);
  attacker.send_input(now + 2, std::nan(""), 1.0);
  attacker.send_input(now + 3, -1e300, 1e300);
  attacker.send_input(0, 40.0, 40.0);  // a tick long past
  attacker.send_input(now + 4, 50.0, 50.0);
  auto moved = attacker.wait_for_snapshot(3s, [&](const client::Snapshot& s) {
    return s.has_applied_input && s.last_applied_input_tick >= now + 4 && s.tick > now + 10;
  });
  ASSERT_TRUE(moved.has_value()) << attacker.last_error().to_string();
  ASSERT_TRUE(moved->own.has_value());
  EXPECT_GT(std::abs(moved->own->velocity.x), 0.0);  // its own body did move
  EXPECT_TRUE(std::isfinite(moved->own->position.x));

  auto after = bystander_->wait_for_snapshot(
      3s, [&](const client::Snapshot& s) { return s.tick >= moved->tick; });
  ASSERT_TRUE(after.has_value());
  std::size_t compared = 0;
  for (const client::BodyState& body : before->bodies) {
    const client::BodyState* now_state = after->find(body.body_id);
    ASSERT_NE(now_state, nullptr) << "body " << body.body_id << " vanished";
    EXPECT_EQ(now_state->position, body.position) << "body " << body.body_id;
    EXPECT_EQ(now_state->velocity, body.velocity) << "body " << body.body_id;
    ++compared;
  }
  EXPECT_GE(compared, 21u);  // the crowd and the bystander
  EXPECT_EQ(before->find(attacker.welcome().body_id), nullptr);
  EXPECT_GE(server_->stats().clamped_inputs, 1u);
  attacker.disconnect();
}

// Every view setting out of range is refused with ERROR_INVALID_VIEW, naming the
// field, and the session is closed; the others are served on (TearDown).
TEST_F(BadInput, ViewSettingsOutOfRangeAreRefusedNamingTheField) {
  start();
  struct Case {
    const char* field;
    std::function<void(pb::ViewRequest&)> set;
  };
  const std::vector<Case> cases = {
      {"position_precision", [](pb::ViewRequest& v) { v.set_position_precision(0.0); }},
      {"position_precision", [](pb::ViewRequest& v) { v.set_position_precision(-0.001); }},
      {"velocity_precision", [](pb::ViewRequest& v) { v.set_velocity_precision(std::nan("")); }},
      {"position_tolerance", [](pb::ViewRequest& v) { v.set_position_tolerance(1e-6); }},
      {"snapshot_interval", [](pb::ViewRequest& v) { v.set_snapshot_interval(0); }},
      {"snapshot_interval", [](pb::ViewRequest& v) { v.set_snapshot_interval(1000000000); }},
      {"window", [](pb::ViewRequest& v) { v.set_window(0); }},
      {"interest_radius", [](pb::ViewRequest& v) { v.set_interest_radius(1e308); }},
      {"interest_radius", [](pb::ViewRequest& v) { v.set_interest_radius(-1.0); }},
      {"interest_rect", [](pb::ViewRequest& v) { v.mutable_interest_rect()->set_max_x(-1.0); }},
      {"byte_budget", [](pb::ViewRequest& v) { v.set_byte_budget(3); }},
      {"encoding", [](pb::ViewRequest& v) { v.set_encoding(static_cast<pb::Encoding>(9)); }},
      {"view_hash_interval", [](pb::ViewRequest& v) { v.set_view_hash_interval(0); }},
      {"view_hash_interval", [](pb::ViewRequest& v) { v.set_view_hash_interval(1001); }},
  };
  for (const Case& c : cases) {
    RawPeer peer(server_->port());
    pb::ClientMessage hello = hello_message("bad-view");
    c.set(*hello.mutable_hello()->mutable_view());
    ASSERT_TRUE(peer.send(hello));
    auto error = peer.receive_error(3s);
    ASSERT_TRUE(error.has_value()) << c.field;
    EXPECT_EQ(error->code(), pb::ERROR_INVALID_VIEW) << c.field;
    EXPECT_TRUE(error->fatal()) << c.field;
    EXPECT_NE(error->message().find(c.field), std::string::npos) << error->message();
    EXPECT_TRUE(peer.wait_closed(3s)) << c.field;
  }
}

}  // namespace
}  // namespace itest
