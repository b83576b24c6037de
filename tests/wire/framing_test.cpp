// Length-delimited framing: round trips, interop with Protobuf's own
// delimited_message_util, split input, and every way a prefix can be bad.
#include "wire/framing.h"

#include <google/protobuf/io/zero_copy_stream_impl_lite.h>
#include <google/protobuf/util/delimited_message_util.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "wire.pb.h"
#include "wire/messages.h"

namespace {

using physics::wire::ClientMessage;
using physics::wire::ServerMessage;
using wire::FrameReader;
using wire::FrameStatus;

std::span<const std::uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

ClientMessage sample_input(std::uint64_t tick) { return wire::make_input(tick, 1.5, -2.25, 7); }

TEST(Framing, RoundTripOfSeveralMessagesFedAtOnce) {
  std::string stream;
  for (std::uint64_t tick = 1; tick <= 3; ++tick) wire::append_frame(sample_input(tick), stream);

  FrameReader reader;
  reader.feed(bytes_of(stream));
  std::string frame;
  for (std::uint64_t tick = 1; tick <= 3; ++tick) {
    ASSERT_EQ(reader.next(frame), FrameStatus::Frame);
    ClientMessage parsed;
    ASSERT_TRUE(wire::parse_client_message(frame, parsed));
    EXPECT_EQ(parsed.input().tick(), tick);
    EXPECT_EQ(parsed.input().ax(), 1.5);
    EXPECT_EQ(parsed.input().ay(), -2.25);
  }
  EXPECT_EQ(reader.next(frame), FrameStatus::NeedMore);
  EXPECT_EQ(reader.buffered_bytes(), 0u);
}

TEST(Framing, OurFramesParseWithProtobufsDelimitedReader) {
  std::string stream;
  wire::append_frame(wire::make_hello("alice", "secret"), stream);
  wire::append_frame(sample_input(42), stream);

  google::protobuf::io::ArrayInputStream input(stream.data(), static_cast<int>(stream.size()));
  ClientMessage first;
  ClientMessage second;
  bool clean_eof = false;
  ASSERT_TRUE(google::protobuf::util::ParseDelimitedFromZeroCopyStream(&first, &input, &clean_eof));
  ASSERT_TRUE(
      google::protobuf::util::ParseDelimitedFromZeroCopyStream(&second, &input, &clean_eof));
  EXPECT_EQ(first.hello().client_name(), "alice");
  EXPECT_EQ(first.hello().access_token(), "secret");
  EXPECT_EQ(second.input().tick(), 42u);
  ClientMessage none;
  EXPECT_FALSE(google::protobuf::util::ParseDelimitedFromZeroCopyStream(&none, &input, &clean_eof));
  EXPECT_TRUE(clean_eof);
}

TEST(Framing, ProtobufsDelimitedWriterIsReadByOurs) {
  std::string stream;
  {
    google::protobuf::io::StringOutputStream output(&stream);
    ServerMessage error = wire::make_error(physics::wire::ERROR_BAD_TOKEN, "wrong token", true);
    ASSERT_TRUE(google::protobuf::util::SerializeDelimitedToZeroCopyStream(error, &output));
    ServerMessage big;
    for (int i = 0; i < 1000; ++i) big.mutable_welcome()->add_bodies()->set_body_id(i);
    ASSERT_TRUE(google::protobuf::util::SerializeDelimitedToZeroCopyStream(big, &output));
  }
  // Our encoder writes the same bytes as Protobuf's.
  std::string ours;
  wire::append_frame(wire::make_error(physics::wire::ERROR_BAD_TOKEN, "wrong token", true), ours);
  EXPECT_EQ(stream.substr(0, ours.size()), ours);

  FrameReader reader;
  reader.feed(bytes_of(stream));
  std::string frame;
  ServerMessage parsed;
  ASSERT_EQ(reader.next(frame), FrameStatus::Frame);
  ASSERT_TRUE(wire::parse_server_message(frame, parsed));
  EXPECT_EQ(parsed.error().code(), physics::wire::ERROR_BAD_TOKEN);
  EXPECT_TRUE(parsed.error().fatal());
  ASSERT_EQ(reader.next(frame), FrameStatus::Frame);
  ASSERT_TRUE(wire::parse_server_message(frame, parsed));
  ASSERT_EQ(parsed.welcome().bodies_size(), 1000);  // a two-byte length prefix
  EXPECT_EQ(parsed.welcome().bodies(999).body_id(), 999u);
}

TEST(Framing, FedOneByteAtATime) {
  std::string stream;
  ServerMessage big;
  for (int i = 0; i < 300; ++i) big.mutable_welcome()->add_bodies()->set_body_id(i);
  wire::append_frame(big, stream);
  wire::append_frame(sample_input(9), stream);

  FrameReader reader;
  std::vector<std::string> frames;
  std::string frame;
  for (const char c : stream) {
    const std::uint8_t byte = static_cast<std::uint8_t>(c);
    reader.feed(std::span<const std::uint8_t>(&byte, 1));
    FrameStatus status;
    while ((status = reader.next(frame)) == FrameStatus::Frame) frames.push_back(frame);
    ASSERT_EQ(status, FrameStatus::NeedMore);
  }
  ASSERT_EQ(frames.size(), 2u);
  ServerMessage first;
  ASSERT_TRUE(wire::parse_server_message(frames[0], first));
  EXPECT_EQ(first.welcome().bodies_size(), 300);
  ClientMessage second;
  ASSERT_TRUE(wire::parse_client_message(frames[1], second));
  EXPECT_EQ(second.input().tick(), 9u);
}

TEST(Framing, EmptyMessageIsAZeroLengthFrame) {
  const std::string stream = wire::encode_frame(ClientMessage{});
  ASSERT_EQ(stream, std::string(1, '\0'));
  FrameReader reader;
  reader.feed(bytes_of(stream));
  std::string frame = "junk";
  ASSERT_EQ(reader.next(frame), FrameStatus::Frame);
  EXPECT_TRUE(frame.empty());
  ClientMessage parsed;
  ASSERT_TRUE(wire::parse_client_message(frame, parsed));
  EXPECT_EQ(parsed.kind_case(), ClientMessage::KIND_NOT_SET);
}

TEST(Framing, TooLargePrefixIsRefusedBeforeTheBodyArrives) {
  FrameReader reader(1024);
  std::string prefix;
  wire::append_varint_prefix(1025, prefix);
  reader.feed(bytes_of(prefix));  // only the prefix: no body byte has arrived
  std::string frame;
  EXPECT_EQ(reader.next(frame), FrameStatus::TooLarge);
  EXPECT_EQ(reader.rejected_length(), 1025u);
  EXPECT_LE(reader.buffered_bytes(), 10u);
}

TEST(Framing, PrefixOfExactlyTheLimitIsAccepted) {
  FrameReader reader(1024);
  std::string stream;
  wire::append_varint_prefix(1024, stream);
  stream.append(1024, '\0');  // 1024 bytes of field-0 garbage: framing does not care
  reader.feed(bytes_of(stream));
  std::string frame;
  ASSERT_EQ(reader.next(frame), FrameStatus::Frame);
  EXPECT_EQ(frame.size(), 1024u);
}

TEST(Framing, HugeLengthsAreTooLargeNotAllocated) {
  FrameReader reader;  // 1 MiB
  std::string prefix;
  wire::append_varint_prefix(UINT64_MAX, prefix);  // the largest valid 10-byte varint
  ASSERT_EQ(prefix.size(), 10u);
  reader.feed(bytes_of(prefix));
  std::string frame;
  EXPECT_EQ(reader.next(frame), FrameStatus::TooLarge);
  EXPECT_EQ(reader.rejected_length(), UINT64_MAX);
}

TEST(Framing, VarintLongerThanTenBytesIsBadPrefix) {
  FrameReader reader;
  const std::string eleven(11, '\x80');
  reader.feed(bytes_of(eleven));
  std::string frame;
  EXPECT_EQ(reader.next(frame), FrameStatus::BadPrefix);
}

TEST(Framing, TenByteVarintThatOverflows64BitsIsBadPrefix) {
  FrameReader reader;
  std::string overflow(9, '\xFF');
  overflow.push_back('\x02');  // bit 64: one past what 64 bits hold
  reader.feed(bytes_of(overflow));
  std::string frame;
  EXPECT_EQ(reader.next(frame), FrameStatus::BadPrefix);
}

TEST(Framing, UnfinishedPrefixWaitsForMore) {
  FrameReader reader;
  const std::string partial(9, '\x80');  // nine continuation bytes: still valid so far
  reader.feed(bytes_of(partial));
  std::string frame;
  EXPECT_EQ(reader.next(frame), FrameStatus::NeedMore);
}

TEST(Framing, BufferStaysBoundedWhileAFrameArrivesInChunks) {
  constexpr std::size_t kMax = 64 * 1024;
  FrameReader reader(kMax);
  std::string stream;
  for (int i = 0; i < 50; ++i) {
    ServerMessage message;
    message.mutable_error()->set_message(std::string(40000, 'x'));
    wire::append_frame(message, stream);
  }
  constexpr std::size_t kChunk = 4096;
  std::size_t most_buffered = 0;
  int frames = 0;
  std::string frame;
  for (std::size_t at = 0; at < stream.size(); at += kChunk) {
    const std::size_t n = std::min(kChunk, stream.size() - at);
    reader.feed(bytes_of(stream).subspan(at, n));
    most_buffered = std::max(most_buffered, reader.buffered_bytes());
    while (reader.next(frame) == FrameStatus::Frame) ++frames;
  }
  EXPECT_EQ(frames, 50);
  EXPECT_LE(most_buffered, kMax + 10 + kChunk);
}

TEST(Framing, RandomBytesNeverCrashAndEndInAVerdict) {
  // A fixed pseudo-random stream: whatever the bytes, the reader answers NeedMore,
  // Frame, TooLarge or BadPrefix and never buffers past its bound.
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  std::string garbage;
  for (int i = 0; i < 100000; ++i) {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    garbage.push_back(static_cast<char>(state & 0xFF));
  }
  for (std::size_t start = 0; start < 64; ++start) {
    FrameReader reader(4096);
    reader.feed(bytes_of(garbage).subspan(start, 8192));
    std::string frame;
    FrameStatus status;
    int frames = 0;
    while ((status = reader.next(frame)) == FrameStatus::Frame) {
      ClientMessage parsed;
      (void)wire::parse_client_message(frame, parsed);  // may or may not parse
      ++frames;
    }
    EXPECT_TRUE(status == FrameStatus::NeedMore || status == FrameStatus::TooLarge ||
                status == FrameStatus::BadPrefix);
    EXPECT_LE(reader.buffered_bytes(), 8192u);
  }
}

}  // namespace
