// The operations endpoint's request reader: complete requests in one piece or
// byte by byte, and what it refuses (too many header bytes, not a request line, bytes
// no header holds), never holding more than its cap whatever it is fed.
#include "ops_http_request.h"

#include <gtest/gtest.h>

#include <string>

namespace {

using server::OpsHttpRequest;
using State = OpsHttpRequest::State;

TEST(OpsHttpRequest, AProbeInOnePiece) {
  OpsHttpRequest request(8192);
  EXPECT_EQ(request.feed("GET /healthz HTTP/1.1\r\nHost: x\r\nUser-Agent: kube-probe\r\n\r\n"),
            State::Complete);
  EXPECT_EQ(request.method(), "GET");
  EXPECT_EQ(request.target(), "/healthz");
}

TEST(OpsHttpRequest, AScrapeByteByByteWithAQueryString) {
  const std::string text = "HEAD /metrics?x=1 HTTP/1.0\n\n";
  OpsHttpRequest request(8192);
  for (std::size_t i = 0; i + 1 < text.size(); ++i) {
    ASSERT_EQ(request.feed(text.substr(i, 1)), State::Incomplete) << i;
  }
  EXPECT_EQ(request.feed(text.substr(text.size() - 1)), State::Complete);
  EXPECT_EQ(request.method(), "HEAD");
  EXPECT_EQ(request.target(), "/metrics");
}

TEST(OpsHttpRequest, HeadersOverTheCapAreRefusedAndNeverHeld) {
  OpsHttpRequest request(1024);
  EXPECT_EQ(request.feed("GET / HTTP/1.1\r\nX-Long: "), State::Incomplete);
  const std::string line(16u << 20, 'a');  // one 16 MiB header line
  EXPECT_EQ(request.feed(line), State::HeaderTooLarge);
  EXPECT_LE(request.held_bytes(), 1024u);
  EXPECT_EQ(request.feed("\r\n\r\n"), State::HeaderTooLarge);  // stays refused
  EXPECT_LE(request.held_bytes(), 1024u);
}

TEST(OpsHttpRequest, ARequestEndingExactlyAtTheCapIsServed) {
  std::string text = "GET /readyz HTTP/1.1\r\nX: ";
  text += std::string(100 - text.size() - 4, 'b') + "\r\n\r\n";
  ASSERT_EQ(text.size(), 100u);
  OpsHttpRequest request(100);
  EXPECT_EQ(request.feed(text), State::Complete);
}

TEST(OpsHttpRequest, WhatIsNotARequestIsMalformed) {
  for (const std::string& text :
       {std::string("GET\r\n\r\n"), std::string("GET /x\r\n\r\n"),
        std::string("GET x HTTP/1.1\r\n\r\n"), std::string("GET /x HTTP/2\r\n\r\n"),
        std::string(" /x HTTP/1.1\r\n\r\n"), std::string("GET /x HTTP/1.1\r\nA: \0\r\n\r\n", 25)}) {
    OpsHttpRequest request(8192);
    EXPECT_EQ(request.feed(text), State::Malformed) << text;
  }
}

}  // namespace
