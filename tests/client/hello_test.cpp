// The Hello the client library builds from its config: the bytes docs/PROTOCOL.md
// shows for a plain one, and every setting carried as the server reads it.
#include <gtest/gtest.h>

#include <string>

#include "client/client.h"
#include "convert.h"
#include "protocol_page.h"
#include "wire.pb.h"
#include "wire/framing.h"
#include "wire/messages.h"
#include "wire/view_settings.h"

namespace {

namespace pb = physics::wire;

// The Hello as the server takes it off the wire.
pb::Hello sent_hello(const client::ClientConfig& config) {
  const pb::ClientMessage message = client::convert::make_hello(config);
  pb::ClientMessage parsed;
  EXPECT_TRUE(wire::parse_client_message(message.SerializeAsString(), parsed));
  EXPECT_TRUE(parsed.has_hello());
  return parsed.hello();
}

TEST(ClientHello, ADefaultConfigSendsThePagesHello) {
  client::ClientConfig config;
  config.name = "ann";
  const auto examples = protocol_page::wire_examples(protocol_page::text());
  ASSERT_GE(examples.size(), 1u);
  EXPECT_EQ(protocol_page::hex(wire::encode_frame(client::convert::make_hello(config))),
            examples[0]);
  const pb::Hello hello = sent_hello(config);
  EXPECT_FALSE(hello.has_view());
  EXPECT_FALSE(hello.has_seat());
  EXPECT_FALSE(hello.has_contacts());
  EXPECT_FALSE(hello.spectate());
}

TEST(ClientHello, TheServerResolvesTheViewTheConfigAsksFor) {
  client::ClientConfig config;
  config.token = "s3cret";
  config.view.encoding = client::Encoding::Exact;
  config.view.position_precision = 0.01;
  config.view.position_tolerance = 0.05;
  config.view.snapshot_interval = 3;
  config.view.window = 8;
  config.view.interest_rect = client::Rect{-5.0, -1.0, 5.0, 9.0};
  config.view.byte_budget = 128;
  config.view.state_hash = true;
  const pb::Hello hello = sent_hello(config);
  EXPECT_EQ(hello.protocol_version(), wire::kProtocolVersion);
  EXPECT_EQ(hello.client_name(), config.name);
  EXPECT_EQ(hello.access_token(), "s3cret");

  wire::ViewSettings settings;
  ASSERT_EQ(wire::resolve_view(hello.view(), 64, settings), "");
  EXPECT_EQ(settings.encoding, pb::ENCODING_EXACT);
  EXPECT_EQ(settings.quantum.position, 0.01);
  EXPECT_EQ(settings.quantum.velocity, wire::ViewSettings{}.quantum.velocity);
  EXPECT_EQ(settings.position_tolerance, 0.05);
  EXPECT_EQ(settings.snapshot_interval, 3u);
  EXPECT_EQ(settings.window, 8u);
  ASSERT_EQ(settings.interest, wire::InterestKind::Rect);
  EXPECT_EQ(settings.interest_rect.min_x(), -5.0);
  EXPECT_EQ(settings.interest_rect.max_y(), 9.0);
  EXPECT_EQ(settings.byte_budget, 128u);
  EXPECT_TRUE(settings.state_hash);
}

TEST(ClientHello, ADefaultViewResolvesToTheServersDefaults) {
  wire::ViewSettings settings;
  ASSERT_EQ(wire::resolve_view(sent_hello(client::ClientConfig{}).view(), 64, settings), "");
  EXPECT_EQ(settings, wire::ViewSettings{});
}

TEST(ClientHello, SpectatorSeatAndContactsAreCarried) {
  client::ClientConfig spectator;
  spectator.spectate = true;
  spectator.contacts = client::ContactSubscription{false, {3, 8}};
  const pb::Hello watching = sent_hello(spectator);
  EXPECT_TRUE(watching.spectate());
  ASSERT_TRUE(watching.has_contacts());
  EXPECT_FALSE(watching.contacts().all());
  ASSERT_EQ(watching.contacts().body_ids_size(), 2);
  EXPECT_EQ(watching.contacts().body_ids(1), 8u);

  // A player's empty subscription asks for its own body's contacts: it must be sent.
  client::ClientConfig player;
  player.seat = 0;
  player.contacts = client::ContactSubscription{};
  const pb::Hello playing = sent_hello(player);
  ASSERT_TRUE(playing.has_seat());
  EXPECT_EQ(playing.seat(), 0u);
  EXPECT_TRUE(playing.has_contacts());
  EXPECT_EQ(playing.contacts().body_ids_size(), 0);
}

TEST(ClientHello, AnOldProtocolVersionIsSentAsConfigured) {
  client::ClientConfig config;
  config.protocol_version = 1;
  EXPECT_EQ(sent_hello(config).protocol_version(), 1u);
}

}  // namespace
