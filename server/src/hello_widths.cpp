#include "hello_widths.h"

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/wire_format_lite.h>

#include <cstdint>
#include <limits>

namespace server {
namespace {

namespace io = google::protobuf::io;
using google::protobuf::internal::WireFormatLite;

// Field numbers (proto/wire.proto).
constexpr int kClientHello = 1;
constexpr int kHelloProtocolVersion = 1;
constexpr int kHelloView = 4;
constexpr int kHelloSeat = 6;
constexpr int kViewEncoding = 1;
constexpr int kViewSnapshotInterval = 6;
constexpr int kViewWindow = 7;
constexpr int kViewByteBudget = 10;

constexpr std::uint64_t kMaxUint32 = std::numeric_limits<std::uint32_t>::max();

// The sub-message of field `number` in `bytes` (the last one, as protobuf merges), or
// nullopt when it is absent or the bytes do not walk.
std::optional<std::string_view> sub_message(std::string_view bytes, int number) {
  io::CodedInputStream in(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                          static_cast<int>(bytes.size()));
  std::optional<std::string_view> found;
  while (const std::uint32_t tag = in.ReadTag()) {
    if (WireFormatLite::GetTagFieldNumber(tag) == number &&
        WireFormatLite::GetTagWireType(tag) == WireFormatLite::WIRETYPE_LENGTH_DELIMITED) {
      std::uint32_t length = 0;
      if (!in.ReadVarint32(&length)) return std::nullopt;
      const int at = in.CurrentPosition();
      if (length > bytes.size() - static_cast<std::size_t>(at)) return std::nullopt;
      found = bytes.substr(static_cast<std::size_t>(at), length);
      if (!in.Skip(static_cast<int>(length))) return std::nullopt;
    } else if (!WireFormatLite::SkipField(&in, tag)) {
      return std::nullopt;
    }
  }
  return found;
}

// Calls check(number, value) for each varint field of `bytes`; stops at the first
// that returns a WideField.
template <typename Check>
std::optional<WideField> each_varint(std::string_view bytes, Check&& check) {
  io::CodedInputStream in(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                          static_cast<int>(bytes.size()));
  while (const std::uint32_t tag = in.ReadTag()) {
    if (WireFormatLite::GetTagWireType(tag) == WireFormatLite::WIRETYPE_VARINT) {
      std::uint64_t value = 0;
      if (!in.ReadVarint64(&value)) return std::nullopt;
      if (auto wide = check(WireFormatLite::GetTagFieldNumber(tag), value)) return wide;
    } else if (!WireFormatLite::SkipField(&in, tag)) {
      return std::nullopt;
    }
  }
  return std::nullopt;
}

std::string too_wide(const char* field, std::uint64_t value, const char* type) {
  return std::string(field) + " " + std::to_string(value) + " does not fit its " + type + " field";
}

}  // namespace

std::optional<WideField> find_wide_hello_field(std::string_view frame) {
  const std::optional<std::string_view> hello = sub_message(frame, kClientHello);
  if (!hello) return std::nullopt;
  auto wide = each_varint(*hello, [](int number, std::uint64_t value) -> std::optional<WideField> {
    if (value <= kMaxUint32) return std::nullopt;
    if (number == kHelloProtocolVersion) {
      return WideField{physics::wire::ERROR_PROTOCOL_VERSION,
                       too_wide("Hello.protocol_version", value, "uint32"),
                       DropReason::ProtocolVersion};
    }
    if (number == kHelloSeat) {
      return WideField{physics::wire::ERROR_SEAT_OUT_OF_RANGE,
                       too_wide("Hello.seat", value, "uint32"), DropReason::SeatOutOfRange};
    }
    return std::nullopt;
  });
  if (wide) return wide;
  const std::optional<std::string_view> view = sub_message(*hello, kHelloView);
  if (!view) return std::nullopt;
  return each_varint(*view, [](int number, std::uint64_t value) -> std::optional<WideField> {
    const char* field = number == kViewSnapshotInterval ? "view.snapshot_interval"
                        : number == kViewWindow         ? "view.window"
                        : number == kViewByteBudget     ? "view.byte_budget"
                                                        : nullptr;
    if (field != nullptr && value > kMaxUint32) {
      return WideField{physics::wire::ERROR_INVALID_VIEW, too_wide(field, value, "uint32"),
                       DropReason::InvalidView};
    }
    // An enum is an int32 on the wire: negative values arrive sign-extended to 64 bits.
    const auto as_signed = static_cast<std::int64_t>(value);
    if (number == kViewEncoding && (as_signed < std::numeric_limits<std::int32_t>::min() ||
                                    as_signed > std::numeric_limits<std::int32_t>::max())) {
      return WideField{physics::wire::ERROR_INVALID_VIEW,
                       too_wide("view.encoding", value, "enum (int32)"), DropReason::InvalidView};
    }
    return std::nullopt;
  });
}

}  // namespace server
