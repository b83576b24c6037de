// The worked byte examples of docs/PROTOCOL.md, read from the page and checked
// against the real encoder, so that the document cannot drift from the wire.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "protocol_page.h"
#include "wire.pb.h"
#include "wire/framing.h"
#include "wire/messages.h"

namespace itest {
namespace {

using protocol_page::hex;

std::vector<std::string> page_examples() {
  return protocol_page::wire_examples(protocol_page::text());
}

TEST(ProtocolDoc, HelloExampleBytes) {
  physics::wire::ClientMessage message;
  message.mutable_hello()->set_protocol_version(wire::kProtocolVersion);
  message.mutable_hello()->set_client_name("ann");
  const auto examples = page_examples();
  ASSERT_GE(examples.size(), 2u);
  EXPECT_EQ(hex(wire::encode_frame(message)), examples[0]);
}

TEST(ProtocolDoc, InputExampleBytes) {
  physics::wire::ClientMessage message;
  message.mutable_input()->set_tick(61);
  message.mutable_input()->set_ax(1.5);
  message.mutable_input()->set_ay(0.0);
  message.mutable_input()->set_sequence(1);
  const auto examples = page_examples();
  ASSERT_GE(examples.size(), 2u);
  EXPECT_EQ(hex(wire::encode_frame(message)), examples[1]);
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
