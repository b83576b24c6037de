// Bad bytes and frames: streams that are not a sequence of ClientMessages, prefixes
// over the limits or malformed, frames cut off. Each is answered with the Error
// PROTOCOL.md names (or, cut off, with none) and a close of that session alone.
#include <gtest/gtest.h>

#include <limits>
#include <optional>
#include <random>

#include "bad_input_fixture.h"
#include "wire/messages.h"

namespace itest {
namespace {

namespace pb = physics::wire;

// What PROTOCOL.md (1.1, 3.1, 3.6) says the server answers a stream of bytes sent
// before Hello and then ended: an Error code, or none when the stream ends inside
// a frame (a connection that breaks mid-frame is closed without a message).
std::optional<pb::ErrorCode> documented_reply(const std::string& bytes) {
  std::uint64_t length = 0;
  std::size_t at = 0;
  for (int shift = 0;; shift += 7, ++at) {
    if (at == bytes.size()) return std::nullopt;  // cut off inside the prefix
    if (at == 10) return pb::ERROR_MALFORMED;     // longer than 10 bytes
    const auto byte = static_cast<std::uint8_t>(bytes[at]);
    if (shift == 63 && (byte & 0x7E) != 0) return pb::ERROR_MALFORMED;  // over 64 bits
    length |= static_cast<std::uint64_t>(byte & 0x7F) << shift;
    if ((byte & 0x80) == 0) break;
  }
  ++at;
  // Before Hello the frame limit is max_hello_bytes (4 KiB), not max_message_bytes.
  if (length > server::ServerConfig{}.max_hello_bytes) return pb::ERROR_MESSAGE_TOO_LARGE;
  if (bytes.size() - at < length) return std::nullopt;  // cut off inside the frame
  pb::ClientMessage message;
  if (!wire::parse_client_message(bytes.substr(at, length), message)) return pb::ERROR_MALFORMED;
  if (message.kind_case() == pb::ClientMessage::KIND_NOT_SET) return pb::ERROR_MALFORMED;
  if (message.kind_case() != pb::ClientMessage::kHello) return pb::ERROR_UNEXPECTED_MESSAGE;
  return pb::ERROR_PROTOCOL_VERSION;  // random bytes never spell a valid Hello
}

TEST_F(BadInput, BytesBeforeHelloGetTheErrorTheProtocolNamesAndAClose) {
  start();
  // First a whole frame of 3 bytes that do not parse: ERROR_MALFORMED, counted so.
  const std::string junk("\x03\xff\xff\xff", 4);
  ASSERT_EQ(documented_reply(junk), pb::ERROR_MALFORMED);
  {
    RawPeer peer(server_->port());
    ASSERT_TRUE(peer.send_bytes(junk));
    const auto error = peer.receive_error(3s);
    ASSERT_TRUE(error.has_value());
    EXPECT_EQ(error->code(), pb::ERROR_MALFORMED) << error->message();
    EXPECT_TRUE(error->fatal());
    EXPECT_TRUE(peer.wait_closed(3s));
    EXPECT_TRUE(
        eventually([&] { return dropped(server_->stats(), server::DropReason::Malformed) == 1u; }));
  }
  int errors = 0;
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    std::mt19937 random(seed);
    // 16 streams of random bytes, and 4 whose prefix promises 100 bytes of which
    // only 50 come before the end of the stream.
    std::string garbage = seed <= 16 ? std::string(2048, '\0') : "\x64" + std::string(50, '\0');
    for (std::size_t i = seed <= 16 ? 0 : 1; i < garbage.size(); ++i) {
      garbage[i] = static_cast<char>(random() & 0xFF);
    }
    const std::optional<pb::ErrorCode> expected = documented_reply(garbage);
    RawPeer peer(server_->port());
    ASSERT_TRUE(peer.connected());
    peer.send_bytes(garbage);
    // Then the end of the stream: garbage whose length prefix promises more than was
    // sent (up to 1 MiB) is cut off, and the server must see that too.
    peer.shutdown_send();
    const auto error = peer.receive_error(3s);
    if (expected) {
      ASSERT_TRUE(error.has_value()) << "seed " << seed << ": expected " << *expected;
      EXPECT_EQ(error->code(), *expected) << "seed " << seed << ": " << error->message();
      EXPECT_TRUE(error->fatal()) << "seed " << seed;
      EXPECT_FALSE(error->message().empty());
      ++errors;
    } else {
      EXPECT_FALSE(error.has_value()) << "seed " << seed << ": " << error->message();
    }
    EXPECT_TRUE(peer.wait_closed(3s)) << "seed " << seed;
  }
  // Both kinds of stream came up, so both branches above were taken.
  EXPECT_GT(errors, 0);
  EXPECT_LE(errors, 16);
  EXPECT_TRUE(eventually([&] { return server_->stats().dropped_total() >= 21u; }));
}

TEST_F(BadInput, RandomBytesAfterWelcomeEndOnlyThatSession) {
  start();
  RawPeer peer(server_->port());
  ASSERT_TRUE(peer.send(hello_message("garbage-after-hello")));
  auto welcome = peer.receive(3s);
  ASSERT_TRUE(welcome && welcome->has_welcome());
  const std::uint64_t body = welcome->welcome().body_id();
  // A frame of the right length whose bytes are not a ClientMessage: field 15 with
  // wire type 7 (invalid), then noise.
  std::string body_bytes = "\x7F\xFF\xFF\xFF\xFF\xFF\xFF\xFF\xFF\xFF\x01 noise";
  peer.send_bytes(varint(body_bytes.size()) + body_bytes);
  EXPECT_TRUE(fatal_error_then_closed(peer, pb::ERROR_MALFORMED));
  EXPECT_TRUE(body_removed(body));
}

TEST_F(BadInput, LengthPrefixOverTheMaximumIsRefusedAndClosed) {
  start();
  RawPeer peer(server_->port());
  ASSERT_TRUE(peer.send(hello_message("too-large")));
  ASSERT_TRUE(peer.receive(3s).has_value());  // Welcome
  // One byte over the 1 MiB limit, and only the prefix: the server must refuse it
  // from the prefix alone, without waiting for (or allocating) the body.
  peer.send_bytes(varint(wire::kDefaultMaxMessageBytes + 1));
  EXPECT_TRUE(fatal_error_then_closed(peer, pb::ERROR_MESSAGE_TOO_LARGE));
  EXPECT_TRUE(eventually(
      [&] { return dropped(server_->stats(), server::DropReason::MessageTooLarge) == 1; }));
}

// A prefix of 2^63 - 1 alone, before Hello: refused from the prefix and counted; the
// bystander keeps getting new ticks (TearDown).
TEST_F(BadInput, HugeLengthPrefixBeforeHelloIsRefused) {
  start();
  RawPeer peer(server_->port());
  peer.send_bytes(varint(std::numeric_limits<std::uint64_t>::max() / 2));
  EXPECT_TRUE(fatal_error_then_closed(peer, pb::ERROR_MESSAGE_TOO_LARGE));
  EXPECT_TRUE(eventually(
      [&] { return dropped(server_->stats(), server::DropReason::MessageTooLarge) == 1; }));
}

TEST_F(BadInput, OverlongVarintPrefixIsMalformed) {
  start();
  RawPeer peer(server_->port());
  peer.send_bytes(std::string(11, '\xFF'));
  // PROTOCOL.md 1.1: a varint longer than 10 bytes is ERROR_MALFORMED, fatal.
  EXPECT_TRUE(fatal_error_then_closed(peer, pb::ERROR_MALFORMED));
}

TEST_F(BadInput, FrameCutOffByADisconnectRemovesTheSession) {
  start();
  std::uint64_t body = 0;
  {
    RawPeer peer(server_->port());
    ASSERT_TRUE(peer.send(hello_message("cut-off")));
    auto welcome = peer.receive(3s);
    ASSERT_TRUE(welcome && welcome->has_welcome());
    body = welcome->welcome().body_id();
    // The prefix promises 50 bytes; 20 come, then the connection goes away.
    std::string partial = varint(50) + std::string(20, '\x08');
    peer.send_bytes(partial);
    peer.close();
  }
  EXPECT_TRUE(body_removed(body));
  EXPECT_TRUE(
      eventually([&] { return dropped(server_->stats(), server::DropReason::Disconnected) == 1; }));
}

}  // namespace
}  // namespace itest
