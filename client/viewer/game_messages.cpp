#include "game_messages.h"

#include <fmt/format.h>

#include "client/client.h"
#include "client/game_message_plan.h"

namespace viewer {

void GameMessages::send_queued(client::Client& connection, std::uint64_t tick) {
  send_queued(
      [&connection](std::uint64_t at, const std::string& payload) {
        return connection.send_game_message(at, payload);
      },
      tick);
}

void GameMessages::send_queued(const std::function<bool(std::uint64_t, const std::string&)>& send,
                               std::uint64_t tick) {
  for (std::size_t n = 0; n < client::kMaxGameMessagesPerTick && !outgoing_.empty(); ++n) {
    if (send(tick, outgoing_.front())) ++sent_;
    outgoing_.pop_front();
  }
}

void GameMessages::received(std::vector<client::GameMessage> messages) {
  for (client::GameMessage& message : messages) {
    ++received_;
    recent_.push_back(std::move(message));
    if (recent_.size() > kShown) recent_.pop_front();
  }
}

std::vector<std::string> GameMessages::panel_lines() const {
  std::vector<std::string> lines;
  lines.push_back(fmt::format("game messages: {} sent, {} received", sent_, received_));
  for (const client::GameMessage& message : recent_)
    lines.push_back(fmt::format("  tick {}: {}", message.tick, message.payload.substr(0, 60)));
  return lines;
}

}  // namespace viewer
