#pragma once
// The game messages of a viewer that plays: those its keys queue, sent with the next
// input (before it, as docs/PROTOCOL.md 3.9 asks, so that a lockstep tick finds
// them), and the last few received from the game, for the panel.
#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include "client/types.h"

namespace client {
class Client;
}

namespace viewer {

class GameMessages {
 public:
  // The panel shows this many, the newest last.
  static constexpr std::size_t kShown = 5;

  void queue(std::string payload) { outgoing_.push_back(std::move(payload)); }
  // Sends what was queued for `tick` (at most 4, the server's limit a tick; the rest
  // wait for the next). Called just before the tick's input.
  void send_queued(client::Client& connection, std::uint64_t tick);
  // The same through `send` (a predicting client's, which predicts them too).
  void send_queued(const std::function<bool(std::uint64_t, const std::string&)>& send,
                   std::uint64_t tick);
  void received(std::vector<client::GameMessage> messages);

  std::uint64_t sent() const { return sent_; }
  std::uint64_t received_count() const { return received_; }
  const std::deque<client::GameMessage>& recent() const { return recent_; }
  // The panel's lines: "game: N sent, M received" and the recent messages, each
  // "tick T: payload" (bytes the panel's font lacks drawn as '?').
  std::vector<std::string> panel_lines() const;

 private:
  std::deque<std::string> outgoing_;
  std::deque<client::GameMessage> recent_;
  std::uint64_t sent_ = 0;
  std::uint64_t received_ = 0;
};

}  // namespace viewer
