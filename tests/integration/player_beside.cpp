#include "player_beside.h"

namespace itest {

PlayerBeside::PlayerBeside(const RunningServer& server, const std::string& name)
    : client_(server.client_config(name)) {
  joined_ = client_.connect(3s);
  if (!joined_) {
    error_ = client_.last_error().to_string();
    return;
  }
  connected_ = true;
  // A lockstep server steps its next tick only once inputs for it arrive.
  client_.send_input(client_.welcome().current_tick + 1, 0.0, 0.0);
  thread_ = std::thread([this] {
    while (!stop_.load()) {
      const auto snapshot = client_.next_snapshot(100ms);
      if (client_.state() != client::ConnectionState::Connected) break;
      if (!snapshot) continue;
      ++snapshots_;
      client_.send_input(snapshot->tick + 1, 0.0, 0.0);
    }
    connected_ = client_.state() == client::ConnectionState::Connected;
  });
}

PlayerBeside::~PlayerBeside() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (joined_) client_.disconnect("done");
}

bool PlayerBeside::gets_snapshots(std::uint64_t more, std::chrono::milliseconds timeout) const {
  const std::uint64_t target = snapshots() + more;
  return eventually([&] { return snapshots() >= target || !connected(); }, timeout) &&
         connected() && snapshots() >= target;
}

}  // namespace itest
