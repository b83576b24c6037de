#include "client/game_message_plan.h"

#include <string>

#include "client/client.h"

namespace client {

std::string check_game_message_plan(const GameMessagePlan& plan) {
  if (plan.payloads.size() > kMaxGameMessagesPerTick) {
    return "at most " + std::to_string(kMaxGameMessagesPerTick) +
           " game messages (the server takes 4 of a client a tick), not " +
           std::to_string(plan.payloads.size());
  }
  for (const std::string& payload : plan.payloads) {
    if (payload.size() > kMaxGameMessageBytes) {
      return "a game message holds at most " + std::to_string(kMaxGameMessageBytes) +
             " bytes; this one has " + std::to_string(payload.size());
    }
  }
  if (plan.every.count() < 0) return "the interval between game messages must not be negative";
  return {};
}

bool GameMessageSender::take_round(std::chrono::steady_clock::time_point now) {
  if (done_ || plan_.payloads.empty()) return false;
  if (started_ && now < next_due_) return false;
  // The next round is due an interval after this one was, not after it went out: a
  // late tick does not push every later round back, nor make a burst of them.
  next_due_ = started_ ? next_due_ + plan_.every : now + plan_.every;
  if (next_due_ <= now) next_due_ = now + plan_.every;
  started_ = true;
  done_ = plan_.every.count() == 0;
  return true;
}

std::size_t GameMessageSender::before_input(Client& client, std::uint64_t tick,
                                            std::chrono::steady_clock::time_point now) {
  return before_input(
      [&client](std::uint64_t at, const std::string& payload) {
        return client.send_game_message(at, payload);
      },
      tick, now);
}

std::size_t GameMessageSender::before_input(const Send& send, std::uint64_t tick,
                                            std::chrono::steady_clock::time_point now) {
  if (!take_round(now)) return 0;
  std::size_t sent = 0;
  for (const std::string& payload : plan_.payloads) {
    if (send(tick, payload)) {
      ++sent;
    } else {
      ++failed_;
    }
  }
  sent_ += sent;
  return sent;
}

}  // namespace client
