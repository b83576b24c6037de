// The Hello's 32-bit fields are checked on the wire before protobuf narrows them: a
// byte_budget of 2^63 would otherwise parse as 0 ("no budget") and a seat of 2^32 + 1
// as seat 1. Each over-wide field is named with the error of its kind; values that
// fit pass, whatever else the frame holds.
#include "hello_widths.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "wire/messages.h"

namespace {

namespace pw = physics::wire;

void append_varint(std::uint64_t value, std::string& out) {
  while (value >= 0x80) {
    out.push_back(static_cast<char>((value & 0x7F) | 0x80));
    value >>= 7;
  }
  out.push_back(static_cast<char>(value));
}

void append_varint_field(int number, std::uint64_t value, std::string& out) {
  append_varint(static_cast<std::uint64_t>(number) << 3, out);
  append_varint(value, out);
}

void append_message_field(int number, const std::string& body, std::string& out) {
  append_varint((static_cast<std::uint64_t>(number) << 3) | 2, out);
  append_varint(body.size(), out);
  out += body;
}

// ClientMessage{hello: {protocol_version: 1, client_name: "x", <hello_extra>,
// view: {<view>}}}.
std::string hello_frame(const std::string& view, const std::string& hello_extra = {}) {
  std::string hello;
  append_varint_field(1, 1, hello);
  append_message_field(2, "x", hello);
  hello += hello_extra;
  append_message_field(4, view, hello);
  std::string frame;
  append_message_field(1, hello, frame);
  return frame;
}

TEST(HelloWidths, AByteBudgetOfTwoToTheSixtyThirdIsRefusedNotReadAsZero) {
  std::string view;
  append_varint_field(10, std::uint64_t{1} << 63, view);
  const std::string frame = hello_frame(view);
  pw::ClientMessage parsed;
  ASSERT_TRUE(wire::parse_client_message(frame, parsed));
  EXPECT_EQ(parsed.hello().view().byte_budget(), 0u);  // what protobuf alone makes of it
  const auto wide = server::find_wide_hello_field(frame);
  ASSERT_TRUE(wide.has_value());
  EXPECT_EQ(wide->code, pw::ERROR_INVALID_VIEW);
  EXPECT_EQ(wide->reason, server::DropReason::InvalidView);
  EXPECT_EQ(wide->text, "view.byte_budget 9223372036854775808 does not fit its uint32 field");
}

TEST(HelloWidths, EveryThirtyTwoBitFieldIsChecked) {
  const std::uint64_t over = (std::uint64_t{1} << 32) + 1;
  for (const int number : {6, 7}) {
    std::string view;
    append_varint_field(number, over, view);
    const auto wide = server::find_wide_hello_field(hello_frame(view));
    ASSERT_TRUE(wide.has_value()) << number;
    EXPECT_EQ(wide->code, pw::ERROR_INVALID_VIEW);
  }
  std::string seat;
  append_varint_field(6, over, seat);
  const auto wide_seat = server::find_wide_hello_field(hello_frame({}, seat));
  ASSERT_TRUE(wide_seat.has_value());
  EXPECT_EQ(wide_seat->code, pw::ERROR_SEAT_OUT_OF_RANGE);
  std::string encoding;
  append_varint_field(1, std::uint64_t{1} << 40, encoding);
  const auto wide_encoding = server::find_wide_hello_field(hello_frame(encoding));
  ASSERT_TRUE(wide_encoding.has_value());
  EXPECT_EQ(wide_encoding->code, pw::ERROR_INVALID_VIEW);
}

TEST(HelloWidths, ValuesThatFitPass) {
  std::string view;
  append_varint_field(1, static_cast<std::uint64_t>(-1), view);  // encoding -1: an int32
  append_varint_field(7, 0xFFFFFFFFu, view);
  append_varint_field(10, 4096, view);
  std::string seat;
  append_varint_field(6, 3, seat);
  EXPECT_FALSE(server::find_wide_hello_field(hello_frame(view, seat)).has_value());
  EXPECT_FALSE(
      server::find_wide_hello_field(wire::make_hello("ann").SerializeAsString()).has_value());
}

}  // namespace
