#pragma once
// Protobuf's standard length-delimited framing (a base-128 varint byte count, then
// the message), as google/protobuf/util/delimited_message_util.h writes it, with a
// limit checked before any body is buffered or allocated.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace google::protobuf {
class MessageLite;
}

namespace wire {

inline constexpr std::size_t kDefaultMaxMessageBytes = 1u << 20;  // 1 MiB

// Appends a base-128 varint (1 to 10 bytes), as the length prefix is written.
void append_varint_prefix(std::uint64_t value, std::string& out);

// Appends varint(size) + the serialized message to `out`.
void append_frame(const google::protobuf::MessageLite& message, std::string& out);
std::string encode_frame(const google::protobuf::MessageLite& message);

enum class FrameStatus {
  NeedMore,   // no whole frame buffered yet
  Frame,      // `frame` holds one message's bytes
  TooLarge,   // the length prefix is over the maximum: the stream is unusable
  BadPrefix,  // the varint is longer than 10 bytes or overflows 64 bits
};

// Incremental reader for a byte stream: feed what arrived, take frames out. The
// limit is checked on the length prefix, before the body is waited for, so a
// caller that feeds chunks of at most C bytes and calls next() until it stops
// returning Frame never holds more than max_message_bytes + 10 + C bytes.
class FrameReader {
 public:
  explicit FrameReader(std::size_t max_message_bytes = kDefaultMaxMessageBytes);
  // Appends received bytes. Call next() until it stops returning Frame.
  void feed(std::span<const std::uint8_t> bytes);
  FrameStatus next(std::string& frame);
  std::size_t buffered_bytes() const;
  std::size_t max_message_bytes() const { return max_; }
  // Changes the limit for the frames not yet taken (the server raises it once a
  // connection has joined).
  void set_max_message_bytes(std::size_t max) { max_ = max; }
  // The length the last TooLarge prefix announced.
  std::uint64_t rejected_length() const { return rejected_length_; }

 private:
  std::size_t max_;
  std::vector<std::uint8_t> buffer_;
  std::size_t read_pos_ = 0;
  std::uint64_t rejected_length_ = 0;
};

}  // namespace wire
