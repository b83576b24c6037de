// The envelope helpers: what they build is what the .proto and docs/PROTOCOL.md say,
// and what parse_*_message accepts.
#include "wire/messages.h"

#include <gtest/gtest.h>
#include <sys/mman.h>

#include <climits>
#include <cstddef>
#include <string>

#include "protocol_page.h"
#include "wire.pb.h"
#include "wire/framing.h"

namespace {

namespace pb = physics::wire;

// The payload of a frame `encode_frame` made (its varint prefix taken off).
std::string payload_of(const pb::ClientMessage& message) { return message.SerializeAsString(); }

pb::ClientMessage round_trip(const pb::ClientMessage& message) {
  pb::ClientMessage parsed;
  EXPECT_TRUE(wire::parse_client_message(payload_of(message), parsed));
  return parsed;
}

TEST(Messages, ErrorCarriesCodeTextAndFatality) {
  const auto message = wire::make_error(pb::ERROR_SERVER_FULL, "full", true);
  ASSERT_TRUE(message.has_error());
  EXPECT_EQ(message.error().code(), pb::ERROR_SERVER_FULL);
  EXPECT_EQ(message.error().message(), "full");
  EXPECT_TRUE(message.error().fatal());
}

TEST(Messages, HelloDefaultsToTheCurrentProtocolVersion) {
  const auto hello = wire::make_hello("bob");
  ASSERT_TRUE(hello.has_hello());
  EXPECT_EQ(hello.hello().protocol_version(), wire::kProtocolVersion);
  EXPECT_EQ(wire::kProtocolVersion, 4u);
  EXPECT_TRUE(hello.hello().access_token().empty());
}

TEST(Messages, APlainHelloAndAnInputAreThePagesExamples) {
  const auto examples = protocol_page::wire_examples(protocol_page::text());
  ASSERT_GE(examples.size(), 2u);
  EXPECT_EQ(protocol_page::hex(wire::encode_frame(wire::make_hello("ann"))), examples[0]);
  EXPECT_EQ(protocol_page::hex(wire::encode_frame(wire::make_hello("ann", wire::HelloOptions{}))),
            examples[0]);
  EXPECT_EQ(protocol_page::hex(wire::encode_frame(wire::make_input(61, 1.5, 0.0, 1))), examples[1]);
}

TEST(Messages, AViewAtEveryDefaultIsLeftOutOfTheHello) {
  wire::HelloOptions options;
  options.view.set_encoding(pb::ENCODING_PREDICTED);
  options.view.set_state_hash(false);
  const pb::ClientMessage hello = round_trip(wire::make_hello("ann", options));
  EXPECT_FALSE(hello.hello().has_view());
}

TEST(Messages, AViewThatAsksForAnythingIsSent) {
  wire::HelloOptions encoding;
  encoding.view.set_encoding(pb::ENCODING_FULL);
  EXPECT_EQ(round_trip(wire::make_hello("a", encoding)).hello().view().encoding(),
            pb::ENCODING_FULL);

  wire::HelloOptions state_hash;
  state_hash.view.set_state_hash(true);
  EXPECT_TRUE(round_trip(wire::make_hello("a", state_hash)).hello().view().state_hash());

  // A field set to zero is still a request (here one the server refuses): it is sent.
  wire::HelloOptions zero_window;
  zero_window.view.set_window(0);
  const pb::ClientMessage hello = round_trip(wire::make_hello("a", zero_window));
  ASSERT_TRUE(hello.hello().has_view());
  EXPECT_TRUE(hello.hello().view().has_window());
}

TEST(Messages, HelloCarriesTokenVersionSpectateAndSeat) {
  wire::HelloOptions options;
  options.access_token = "s3cret";
  options.protocol_version = 7;
  options.spectate = true;
  options.seat = 0;  // seat 0 is a request too, not "absent"
  const pb::Hello hello = round_trip(wire::make_hello("ann", options)).hello();
  EXPECT_EQ(hello.client_name(), "ann");
  EXPECT_EQ(hello.access_token(), "s3cret");
  EXPECT_EQ(hello.protocol_version(), 7u);
  EXPECT_TRUE(hello.spectate());
  ASSERT_TRUE(hello.has_seat());
  EXPECT_EQ(hello.seat(), 0u);

  const pb::Hello plain = round_trip(wire::make_hello("ann", wire::HelloOptions{})).hello();
  EXPECT_FALSE(plain.spectate());
  EXPECT_FALSE(plain.has_seat());
  EXPECT_FALSE(plain.has_contacts());
}

TEST(Messages, AnEmptyContactSubscriptionIsSentAndAnAbsentOneIsNot) {
  wire::HelloOptions own;
  own.contacts.emplace();  // a player's own body's contacts
  EXPECT_TRUE(round_trip(wire::make_hello("p", own)).hello().has_contacts());

  wire::HelloOptions listed;
  listed.contacts.emplace().add_body_ids(5);
  listed.contacts->add_body_ids(9);
  const pb::ContactSubscription sent = round_trip(wire::make_hello("s", listed)).hello().contacts();
  ASSERT_EQ(sent.body_ids_size(), 2);
  EXPECT_EQ(sent.body_ids(0), 5u);
  EXPECT_EQ(sent.body_ids(1), 9u);
  EXPECT_FALSE(sent.all());
}

TEST(Messages, EveryClientEnvelopeParsesAsItsKind) {
  const pb::ClientMessage input = round_trip(wire::make_input(9, -1.25, 2.5, 3));
  ASSERT_TRUE(input.has_input());
  EXPECT_EQ(input.input().tick(), 9u);
  EXPECT_EQ(input.input().ax(), -1.25);
  EXPECT_EQ(input.input().ay(), 2.5);
  EXPECT_EQ(input.input().sequence(), 3u);

  const pb::ClientMessage ack = round_trip(wire::make_ack(41));
  ASSERT_TRUE(ack.has_ack());
  EXPECT_EQ(ack.ack().tick(), 41u);

  const pb::ClientMessage ping = round_trip(wire::make_ping(7, 123456789));
  ASSERT_TRUE(ping.has_ping());
  EXPECT_EQ(ping.ping().nonce(), 7u);
  EXPECT_EQ(ping.ping().client_time_ns(), 123456789u);

  const pb::ClientMessage bye = round_trip(wire::make_bye("done"));
  ASSERT_TRUE(bye.has_bye());
  EXPECT_EQ(bye.bye().reason(), "done");

  // An empty message still sets the envelope's kind: its bytes are not empty.
  const pb::ClientMessage full = wire::make_full_state_request();
  EXPECT_FALSE(payload_of(full).empty());
  EXPECT_TRUE(round_trip(full).has_full_state_request());
}

TEST(Messages, GarbageDoesNotParse) {
  pb::ClientMessage out;
  // Field 1 (hello) declared length-delimited with a length running past the end.
  EXPECT_FALSE(wire::parse_client_message(std::string("\x0a\x7f\x01", 3), out));
  // A wire type that does not exist (7).
  EXPECT_FALSE(wire::parse_client_message(std::string("\x0f", 1), out));
  pb::ServerMessage server_out;
  EXPECT_FALSE(wire::parse_server_message(std::string("\x0a\x7f\x01", 3), server_out));
  EXPECT_FALSE(wire::parse_server_message(std::string("\x0f", 1), server_out));
}

TEST(Messages, AStringThatIsNotUtf8DoesNotParseAtEitherEnd) {
  pb::ClientMessage bye = wire::make_bye("x");
  std::string bytes = payload_of(bye);
  bytes.back() = '\xff';  // the reason's one byte
  pb::ClientMessage client_out;
  EXPECT_FALSE(wire::parse_client_message(bytes, client_out));

  std::string error = wire::make_error(pb::ERROR_MALFORMED, "x", true).SerializeAsString();
  const std::size_t at = error.find('x');
  ASSERT_NE(at, std::string::npos);
  error[at] = '\xff';
  pb::ServerMessage server_out;
  EXPECT_FALSE(wire::parse_server_message(error, server_out));
}

TEST(Messages, AnEnvelopeWithNoKindParsesAndSaysSo) {
  pb::ClientMessage client_out;
  ASSERT_TRUE(wire::parse_client_message("", client_out));
  EXPECT_EQ(client_out.kind_case(), pb::ClientMessage::KIND_NOT_SET);
  pb::ServerMessage server_out;
  ASSERT_TRUE(wire::parse_server_message("", server_out));
  EXPECT_EQ(server_out.kind_case(), pb::ServerMessage::KIND_NOT_SET);
}

// Protobuf parses at most INT_MAX bytes at once; a longer buffer is refused before
// any byte is read. The buffer is address space only (no page may be touched: a read
// would fault), so the test costs no memory.
TEST(Messages, MoreBytesThanProtobufCanParseAreRefusedUnread) {
  const std::size_t size = static_cast<std::size_t>(INT_MAX) + 1;
  void* region = mmap(nullptr, size, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  ASSERT_NE(region, MAP_FAILED);
  const std::string_view huge(static_cast<const char*>(region), size);
  pb::ClientMessage client_out = wire::make_ack(1);
  EXPECT_FALSE(wire::parse_client_message(huge, client_out));
  EXPECT_EQ(client_out.kind_case(), pb::ClientMessage::KIND_NOT_SET);  // nothing stale left
  pb::ServerMessage server_out;
  EXPECT_FALSE(wire::parse_server_message(huge, server_out));
  munmap(region, size);
}

TEST(Messages, ErrorCodeNamesMatchTheProto) {
  EXPECT_EQ(wire::error_code_name(pb::ERROR_PROTOCOL_VERSION), "ERROR_PROTOCOL_VERSION");
}

}  // namespace
