// The handshake line physics-server prints once listening, parsed as a test in any
// language would parse it.
#include <gtest/gtest.h>

#include "physics_testing/server_process.h"

namespace physics_testing {
namespace {

TEST(ListeningLine, GivesTheAddressAndPort) {
  const auto endpoint = parse_listening_line("listening on 127.0.0.1:7777");
  ASSERT_TRUE(endpoint.has_value());
  EXPECT_EQ(endpoint->host, "127.0.0.1");
  EXPECT_EQ(endpoint->port, 7777);
}

TEST(ListeningLine, SplitsAnIpv6AddressAtItsLastColon) {
  const auto endpoint = parse_listening_line("listening on ::1:40000");
  ASSERT_TRUE(endpoint.has_value());
  EXPECT_EQ(endpoint->host, "::1");
  EXPECT_EQ(endpoint->port, 40000);
}

TEST(ListeningLine, ConnectsToLoopbackForAWildcardAddress) {
  EXPECT_EQ(parse_listening_line("listening on 0.0.0.0:5000")->host, "127.0.0.1");
  EXPECT_EQ(parse_listening_line("listening on :::5000")->host, "::1");
}

TEST(ListeningLine, AcceptsACarriageReturn) {
  EXPECT_EQ(parse_listening_line("listening on 127.0.0.1:1\r")->port, 1);
}

TEST(ListeningLine, RefusesEveryOtherLine) {
  for (const char* line :
       {"", "listening on", "listening on 127.0.0.1",
        "listening on 127.0.0.1:", "listening on :7777", "listening on 127.0.0.1:0",
        "listening on 127.0.0.1:65536", "listening on 127.0.0.1:12ab", "listening on 127.0.0.1:-1",
        "Listening on 127.0.0.1:7", " listening on 127.0.0.1:7", "serving at 60 ticks/s"}) {
    EXPECT_FALSE(parse_listening_line(line).has_value()) << "'" << line << "'";
  }
}

}  // namespace
}  // namespace physics_testing
