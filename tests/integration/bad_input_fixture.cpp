#include "bad_input_fixture.h"

namespace itest {

void BadInput::start(server::ServerConfig config, scene::SceneDef scene) {
  max_queued_snapshots_ = 12;  // the default window: no client holds more
  server_ = std::make_unique<RunningServer>(config, std::move(scene));
  bystander_ = std::make_unique<client::Client>(server_->client_config("bystander"));
  ASSERT_TRUE(bystander_->connect(3s)) << bystander_->last_error().to_string();
  auto first = bystander_->next_snapshot(3s);
  ASSERT_TRUE(first.has_value());
  bystander_tick_ = first->tick;
}

void BadInput::TearDown() {
  if (!server_ || HasFatalFailure()) return;
  // The bystander is still in its session and still gets new ticks.
  auto snapshot = bystander_->newest_snapshot(3s);
  ASSERT_TRUE(snapshot.has_value()) << bystander_->last_error().to_string();
  EXPECT_EQ(bystander_->state(), client::ConnectionState::Connected);
  EXPECT_GT(snapshot->tick, bystander_tick_);
  EXPECT_NE(snapshot->find(bystander_->welcome().body_id), nullptr);
  // A fresh client is served correctly.
  EXPECT_EQ(check_server_serves(*server_), "");
  // Queues stayed bounded, and nothing is left behind: only the bystander's
  // connection stays open.
  EXPECT_LE(server_->stats().peak_queued_snapshots, max_queued_snapshots_ + 1);
  EXPECT_TRUE(eventually([&] {
    const auto stats = server_->stats();
    return stats.open_connections == 1 && stats.connected_clients == 1;
  })) << "open "
      << server_->stats().open_connections << ", joined " << server_->stats().connected_clients;
}

bool BadInput::body_removed(std::uint64_t body) {
  return bystander_
      ->wait_for_snapshot(3s, [&](const client::Snapshot& s) { return s.find(body) == nullptr; })
      .has_value();
}

std::string varint(std::uint64_t value) {
  std::string out;
  while (value >= 0x80) {
    out.push_back(static_cast<char>((value & 0x7F) | 0x80));
    value >>= 7;
  }
  out.push_back(static_cast<char>(value));
  return out;
}

::testing::AssertionResult fatal_error_then_closed(RawPeer& peer, physics::wire::ErrorCode code) {
  const auto error = peer.receive_error(3s);
  if (!error) return ::testing::AssertionFailure() << "no Error arrived";
  if (error->code() != code) {
    return ::testing::AssertionFailure()
           << "Error " << physics::wire::ErrorCode_Name(error->code()) << " (" << error->message()
           << "), expected " << physics::wire::ErrorCode_Name(code);
  }
  if (!error->fatal()) return ::testing::AssertionFailure() << "the Error is not fatal";
  if (!peer.wait_closed(3s)) return ::testing::AssertionFailure() << "the server kept it open";
  return ::testing::AssertionSuccess();
}

}  // namespace itest
