// The worked byte examples of docs/PROTOCOL.md, checked against the real encoder,
// so that the document cannot drift from the wire.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "wire.pb.h"
#include "wire/framing.h"

namespace itest {
namespace {

std::string hex(const std::string& bytes) {
  std::string out;
  for (const char c : bytes) {
    char buffer[4];
    std::snprintf(buffer, sizeof buffer, "%02x ", static_cast<unsigned char>(c));
    out += buffer;
  }
  if (!out.empty()) out.pop_back();
  return out;
}

TEST(ProtocolDoc, HelloExampleBytes) {
  physics::wire::ClientMessage message;
  message.mutable_hello()->set_protocol_version(1);
  message.mutable_hello()->set_client_name("ann");
  EXPECT_EQ(hex(wire::encode_frame(message)), "09 0a 07 08 01 12 03 61 6e 6e");
}

TEST(ProtocolDoc, InputExampleBytes) {
  physics::wire::ClientMessage message;
  message.mutable_input()->set_tick(61);
  message.mutable_input()->set_ax(1.5);
  message.mutable_input()->set_ay(0.0);
  message.mutable_input()->set_sequence(1);
  EXPECT_EQ(hex(wire::encode_frame(message)), "0f 12 0d 08 3d 11 00 00 00 00 00 00 f8 3f 20 01");
}

TEST(ProtocolDoc, VarintOf300) {
  // A 300-byte payload gets the two-byte prefix ac 02.
  physics::wire::ClientMessage message;
  message.mutable_bye()->set_reason(std::string(294, 'x'));
  const std::string frame = wire::encode_frame(message);
  ASSERT_EQ(frame.size(), 302u);
  EXPECT_EQ(hex(frame.substr(0, 2)), "ac 02");
}

}  // namespace
}  // namespace itest
