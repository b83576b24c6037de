#pragma once
// A real player that plays on its own thread while a test attacks the server: it
// joins, then takes every snapshot (acknowledging it) and sends an input each tick,
// so the attack tests can check that it kept being served, by counting snapshots.
#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

#include "harness.h"

namespace itest {

class PlayerBeside {
 public:
  // Joins at once; joined() says whether it did (last_error() why not).
  PlayerBeside(const RunningServer& server, const std::string& name = "player");
  ~PlayerBeside();
  PlayerBeside(const PlayerBeside&) = delete;
  PlayerBeside& operator=(const PlayerBeside&) = delete;

  bool joined() const { return joined_; }
  const std::string& last_error() const { return error_; }
  // Snapshots taken so far (safe from the test's thread).
  std::uint64_t snapshots() const { return snapshots_.load(); }
  // True while the session is up.
  bool connected() const { return connected_.load(); }
  // Waits until `more` further snapshots have arrived; false on timeout or if dropped.
  bool gets_snapshots(std::uint64_t more = 3, std::chrono::milliseconds timeout = 3s) const;

 private:
  client::Client client_;
  bool joined_ = false;
  std::string error_;
  std::atomic<std::uint64_t> snapshots_{0};
  std::atomic<bool> connected_{false};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace itest
