// The envelope helpers: what they build is what the .proto says.
#include "wire/messages.h"

#include <gtest/gtest.h>

#include "wire.pb.h"

namespace {

TEST(Messages, ErrorCarriesCodeTextAndFatality) {
  const auto message = wire::make_error(physics::wire::ERROR_SERVER_FULL, "full", true);
  ASSERT_TRUE(message.has_error());
  EXPECT_EQ(message.error().code(), physics::wire::ERROR_SERVER_FULL);
  EXPECT_EQ(message.error().message(), "full");
  EXPECT_TRUE(message.error().fatal());
}

TEST(Messages, HelloDefaultsToTheCurrentProtocolVersion) {
  const auto hello = wire::make_hello("bob");
  ASSERT_TRUE(hello.has_hello());
  EXPECT_EQ(hello.hello().protocol_version(), wire::kProtocolVersion);
  EXPECT_EQ(wire::kProtocolVersion, 2u);
  EXPECT_TRUE(hello.hello().access_token().empty());
}

TEST(Messages, GarbageDoesNotParse) {
  physics::wire::ClientMessage out;
  // Field 1 (hello) declared length-delimited with a length running past the end.
  EXPECT_FALSE(wire::parse_client_message(std::string("\x0a\x7f\x01", 3), out));
  // A wire type that does not exist (7).
  EXPECT_FALSE(wire::parse_client_message(std::string("\x0f", 1), out));
}

TEST(Messages, ErrorCodeNamesMatchTheProto) {
  EXPECT_EQ(wire::error_code_name(physics::wire::ERROR_PROTOCOL_VERSION), "ERROR_PROTOCOL_VERSION");
}

}  // namespace
