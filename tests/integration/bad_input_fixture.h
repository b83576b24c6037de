#pragma once
// The fixture of the bad-input tests (bad_input_*_test.cpp). Every test runs a real
// server with a well-behaved bystander client connected; after the attack the
// bystander is still served, a fresh client is served, and the server holds no more
// connections than it should.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "harness.h"

namespace itest {

class BadInput : public ::testing::Test {
 protected:
  // Starts the server and connects the bystander (a fatal failure when it cannot).
  void start(server::ServerConfig config = test_config(),
             scene::SceneDef scene = scene::default_scene());

  // The checks every bad-input test ends with.
  void TearDown() override;

  // Waits until the bystander's snapshots no longer hold `body` (it was removed).
  bool body_removed(std::uint64_t body);

  std::unique_ptr<RunningServer> server_;
  std::unique_ptr<client::Client> bystander_;
  std::uint64_t bystander_tick_ = 0;
  std::size_t max_queued_snapshots_ = 0;
};

// Whether the peer got a fatal Error with `code` and the server then closed the
// connection; the failure says what came instead.
::testing::AssertionResult fatal_error_then_closed(RawPeer& peer, physics::wire::ErrorCode code);

// `value` as a varint, the way a length prefix is written, for prefixes no encoder
// would send.
std::string varint(std::uint64_t value);

}  // namespace itest
