// Length-delimited framing: round trips, interop with Protobuf's own
// delimited_message_util, split input, and every way a prefix can be bad.
#include "wire/framing.h"

#include <google/protobuf/io/zero_copy_stream_impl_lite.h>
#include <google/protobuf/util/delimited_message_util.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
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

// What a reader with limit `max` must make of `stream`, worked out here from the
// format (a base-128 varint of at most 10 bytes, the 10th carrying one bit, then
// that many bytes): the frames in order, then the verdict it stops on.
struct Reading {
  std::vector<std::string> frames;
  FrameStatus verdict = FrameStatus::NeedMore;
};

Reading reference_reading(const std::string& stream, std::size_t max) {
  Reading reading;
  std::size_t at = 0;
  for (;;) {
    std::uint64_t length = 0;
    std::size_t prefix = 0;
    for (;;) {
      if (at + prefix == stream.size()) return reading;  // NeedMore
      const auto byte = static_cast<std::uint8_t>(stream[at + prefix]);
      if (prefix == 9 && byte > 1) {
        reading.verdict = FrameStatus::BadPrefix;
        return reading;
      }
      length |= static_cast<std::uint64_t>(byte & 0x7F) << (7 * prefix);
      ++prefix;
      if ((byte & 0x80) == 0) break;
      if (prefix == 10) {
        reading.verdict = FrameStatus::BadPrefix;
        return reading;
      }
    }
    if (length > max) {
      reading.verdict = FrameStatus::TooLarge;
      return reading;
    }
    if (stream.size() - at - prefix < length) return reading;  // NeedMore
    reading.frames.push_back(stream.substr(at + prefix, static_cast<std::size_t>(length)));
    at += prefix + static_cast<std::size_t>(length);
  }
}

TEST(Framing, RandomBytesGiveTheFramesAndVerdictTheFormatSays) {
  // Fixed pseudo-random streams, fed in chunks as a socket would: the reader must
  // give exactly the frames and the verdict that the format gives, and never
  // buffer more than max_message_bytes + 10 + the chunk size (framing.h).
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  std::string garbage;
  for (int i = 0; i < 100000; ++i) {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    garbage.push_back(static_cast<char>(state & 0xFF));
  }
  constexpr std::size_t kMax = 4096;
  constexpr std::size_t kChunk = 256;
  int frames_seen = 0;
  int too_large_seen = 0;
  for (std::size_t start = 0; start < 64; ++start) {
    const std::string stream = garbage.substr(start);
    const Reading expected = reference_reading(stream, kMax);
    FrameReader reader(kMax);
    std::vector<std::string> frames;
    FrameStatus status = FrameStatus::NeedMore;
    std::size_t most_buffered = 0;
    std::string frame;
    // Fed until the reader gives up on the stream (TooLarge, BadPrefix) or it ends.
    for (std::size_t at = 0; at < stream.size() && status == FrameStatus::NeedMore; at += kChunk) {
      reader.feed(bytes_of(stream).subspan(at, std::min(kChunk, stream.size() - at)));
      most_buffered = std::max(most_buffered, reader.buffered_bytes());
      while ((status = reader.next(frame)) == FrameStatus::Frame) {
        ClientMessage parsed;
        (void)wire::parse_client_message(frame, parsed);  // may or may not parse
        frames.push_back(frame);
      }
    }
    EXPECT_EQ(frames, expected.frames) << "from byte " << start;
    EXPECT_EQ(status, expected.verdict) << "from byte " << start;
    EXPECT_LE(most_buffered, kMax + 10 + kChunk) << "from byte " << start;
    frames_seen += static_cast<int>(frames.size());
    too_large_seen += status == FrameStatus::TooLarge ? 1 : 0;
  }
  // The streams exercise the reader: frames come out, and most end on a length
  // over the limit.
  EXPECT_GT(frames_seen, 64);
  EXPECT_GT(too_large_seen, 32);
  std::printf("random bytes: %d frames, %d of 64 streams end TooLarge\n", frames_seen,
              too_large_seen);
}

}  // namespace
