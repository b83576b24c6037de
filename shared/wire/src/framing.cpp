#include "wire/framing.h"

#include <google/protobuf/message_lite.h>

#include <algorithm>

namespace wire {
namespace {

constexpr std::size_t kMaxVarintBytes = 10;

void append_varint(std::uint64_t value, std::string& out) {
  while (value >= 0x80) {
    out.push_back(static_cast<char>((value & 0x7F) | 0x80));
    value >>= 7;
  }
  out.push_back(static_cast<char>(value));
}

enum class PrefixStatus { NeedMore, Ok, Bad };

// Decodes a base-128 varint from [data, data+size). A varint of 10 bytes may only
// carry one bit in its last byte (64 = 9*7 + 1); anything more overflows.
PrefixStatus decode_varint(const std::uint8_t* data, std::size_t size, std::uint64_t& value,
                           std::size_t& used) {
  value = 0;
  for (std::size_t i = 0; i < kMaxVarintBytes; ++i) {
    if (i == size) return PrefixStatus::NeedMore;
    const std::uint8_t byte = data[i];
    if (i == kMaxVarintBytes - 1 && byte > 1) return PrefixStatus::Bad;
    value |= static_cast<std::uint64_t>(byte & 0x7F) << (7 * i);
    if ((byte & 0x80) == 0) {
      used = i + 1;
      return PrefixStatus::Ok;
    }
  }
  return PrefixStatus::Bad;
}

}  // namespace

void append_frame(const google::protobuf::MessageLite& message, std::string& out) {
  const std::size_t size = message.ByteSizeLong();
  append_varint(size, out);
  const std::size_t start = out.size();
  out.resize(start + size);
  message.SerializeWithCachedSizesToArray(reinterpret_cast<std::uint8_t*>(out.data() + start));
}

std::string encode_frame(const google::protobuf::MessageLite& message) {
  std::string out;
  append_frame(message, out);
  return out;
}

void append_varint_prefix(std::uint64_t value, std::string& out) { append_varint(value, out); }

FrameReader::FrameReader(std::size_t max_message_bytes) : max_(max_message_bytes) {}

void FrameReader::feed(std::span<const std::uint8_t> bytes) {
  // Consumed bytes are dropped before appending, so what stays buffered is at most
  // one unfinished frame plus what this call adds.
  if (read_pos_ > 0) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(read_pos_));
    read_pos_ = 0;
  }
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

FrameStatus FrameReader::next(std::string& frame) {
  const std::uint8_t* data = buffer_.data() + read_pos_;
  const std::size_t available = buffer_.size() - read_pos_;
  std::uint64_t length = 0;
  std::size_t prefix = 0;
  switch (decode_varint(data, available, length, prefix)) {
    case PrefixStatus::NeedMore:
      return FrameStatus::NeedMore;
    case PrefixStatus::Bad:
      return FrameStatus::BadPrefix;
    case PrefixStatus::Ok:
      break;
  }
  if (length > max_) {
    rejected_length_ = length;
    return FrameStatus::TooLarge;
  }
  if (available - prefix < length) return FrameStatus::NeedMore;
  const auto* begin = reinterpret_cast<const char*>(data + prefix);
  frame.assign(begin, static_cast<std::size_t>(length));
  read_pos_ += prefix + static_cast<std::size_t>(length);
  if (read_pos_ == buffer_.size()) {
    buffer_.clear();
    read_pos_ = 0;
  }
  return FrameStatus::Frame;
}

std::size_t FrameReader::buffered_bytes() const { return buffer_.size() - read_pos_; }

}  // namespace wire
