#pragma once
// Game messages a tool sends on a schedule (physics-client --game-message, and its
// bots): every payload once at the first tick an input goes out for, or again every
// `every` after that. The messages go out just before that tick's input, on the same
// connection, so that a lockstep tick finds them (docs/PROTOCOL.md 3.9).
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace client {

class Client;

// The server takes at most this many bytes of payload, and this many messages of
// one client for one tick (docs/PROTOCOL.md 3.9).
inline constexpr std::size_t kMaxGameMessageBytes = 256;
inline constexpr std::size_t kMaxGameMessagesPerTick = 4;

struct GameMessagePlan {
  std::vector<std::string> payloads;   // all sent together, in this order
  std::chrono::milliseconds every{0};  // 0: once
};

// Empty when the plan is one the server takes; else why not, for a person.
std::string check_game_message_plan(const GameMessagePlan& plan);

class GameMessageSender {
 public:
  explicit GameMessageSender(GameMessagePlan plan) : plan_(std::move(plan)) {}

  // Called with the tick of each input about to be sent: sends the plan's payloads
  // for that tick when they are due at `now`. Returns how many were sent.
  std::size_t before_input(Client& client, std::uint64_t tick,
                           std::chrono::steady_clock::time_point now);
  // The same through `send` (PredictingClient::send_game_message, which also hands
  // the message to the prediction): true when the message went out.
  using Send = std::function<bool(std::uint64_t tick, const std::string& payload)>;
  std::size_t before_input(const Send& send, std::uint64_t tick,
                           std::chrono::steady_clock::time_point now);
  // True when a round of the plan is due at `now`, and counts it as taken: the first
  // call, then (with an interval) once `every` has passed since the last round was due.
  bool take_round(std::chrono::steady_clock::time_point now);
  std::uint64_t sent() const { return sent_; }
  // Sends that failed (the connection was lost).
  std::uint64_t failed() const { return failed_; }

 private:
  GameMessagePlan plan_;
  bool started_ = false;
  bool done_ = false;
  std::chrono::steady_clock::time_point next_due_{};
  std::uint64_t sent_ = 0;
  std::uint64_t failed_ = 0;
};

}  // namespace client
