#pragma once
// A player's input loop over a real path: inputs go out on the client's own clock,
// ahead of the server by the input delay (input_clock.h), not one round trip after
// each snapshot, so a lockstep server keeps its tick rate at any round trip and a
// fixed-rate server applies each input at the tick it names. Pings measure the round
// trip; snapshots and their input margins keep the clock and the delay in step.
//
//   client::InputPacer pacer(client, {});  // the tick rate is Welcome.tick_rate
//   while (auto snapshot = pacer.poll(deadline, [](std::uint64_t tick) { return a(tick); }))
//     draw(*snapshot);
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>

#include "client/client.h"
#include "client/input_clock.h"

namespace client {

enum class InputSchedule {
  // Ahead of the server by the input delay, on the client's own clock (the default).
  Clock,
  // The input for T + after_snapshot_lead once the snapshot of T has arrived: a
  // lockstep server then waits a round trip for every tick. For comparison.
  AfterSnapshot,
};

struct PacerConfig {
  InputSchedule schedule = InputSchedule::Clock;
  std::uint64_t after_snapshot_lead = 1;
  // tick_rate 0 (the default) takes Welcome.tick_rate.
  InputClockConfig clock;
  // Pings for the round trip, this often.
  std::chrono::milliseconds ping_interval{250};
  // poll() also returns (nullopt) as soon as it has sent an input, so that a caller
  // that predicts can show it at once (client/predicting_client.h).
  bool return_after_send = false;
};

struct PacerStats {
  std::uint64_t inputs_sent = 0;
  std::uint64_t pings_sent = 0;
  std::uint64_t margins_seen = 0;
  std::uint64_t late_margins = 0;  // reported negative: the input was late
};

class InputPacer {
 public:
  // The acceleration to send for `tick`; called once per input sent, just before.
  using InputFor = std::function<Vec2(std::uint64_t tick)>;

  // `client` is connected (a player). In lockstep every tick gets an input, in
  // order; at a fixed rate only the newest tick due (an input holds until the next).
  InputPacer(Client& client, PacerConfig config);

  // Sends what falls due until a snapshot arrives (returned, the clock fed with it)
  // or `deadline` passes or the session ends (nullopt; the client's state says which).
  std::optional<Snapshot> poll(std::chrono::steady_clock::time_point deadline,
                               const InputFor& input);

  const InputClock& clock() const { return clock_; }
  const PacerStats& stats() const { return stats_; }
  // The newest tick an input was sent for (0: none yet).
  std::uint64_t last_sent() const { return last_sent_; }

 private:
  // Sends the inputs up to `due` not sent yet: every tick in lockstep, else the newest.
  bool send_through(std::uint64_t due, const InputFor& input);
  void take_pongs();

  Client& client_;
  PacerConfig config_;
  InputClock clock_;
  bool lockstep_;
  std::uint64_t newest_seen_;  // the newest tick the server is known to have stepped
  std::uint64_t last_sent_ = 0;
  std::uint64_t next_nonce_ = 1;
  std::chrono::steady_clock::time_point started_;
  std::chrono::steady_clock::time_point next_ping_{};
  PacerStats stats_;
};

}  // namespace client
