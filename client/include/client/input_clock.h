#pragma once
// When a player sends the input for which tick: the client's estimate of the
// server's tick, and the input delay. Inputs are sent ahead of the server by a lead
// of about the one-way delay plus the jitter, so that each arrives just before its
// tick is due (Overwatch's input buffer; GGPO's and Quantum's input delay). The
// server reports in each snapshot how early the client's inputs arrived
// (Snapshot.input_margin_us); the lead grows at once when one arrives with less than
// `safety` to spare, and shrinks by half the spare while every input of a second
// arrived with more. docs/PROTOCOL.md 3.4. No sockets, no clock: time is passed in.
#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>

namespace client {

struct InputClockConfig {
  double tick_rate = 0.0;  // Welcome.tick_rate (InputPacer fills it in when 0)
  // Ticks ahead of the server's tick that inputs are sent for. Unset: chosen from
  // the round trip and adapted to the margins the server reports.
  std::optional<std::uint32_t> fixed_delay;
  // The least margin the adaptive lead keeps above the worst arrival.
  std::chrono::microseconds safety{2000};
  // The largest delay, in ticks (keep it below Welcome.max_ticks_ahead).
  std::uint32_t max_delay = 100;
};

class InputClock {
 public:
  using time_point = std::chrono::steady_clock::time_point;

  explicit InputClock(InputClockConfig config);

  // The server stepped tick `tick` (a snapshot of it arrived at `received`).
  void on_tick_seen(std::uint64_t tick, time_point received);
  // The server is at `tick` and steps only when inputs arrive (a lockstep Welcome):
  // until a tick is seen stepped, its tick is taken to stand still there.
  void on_waiting_at(std::uint64_t tick);
  // A Ping's round trip, answered at `received`.
  void on_round_trip(std::chrono::nanoseconds round_trip, time_point received);
  // Snapshot.input_margin_us, in a snapshot that arrived at `received`.
  void on_margin(std::chrono::microseconds margin, time_point received);

  // The server's tick at `now`, with its fraction: the tick it last stepped plus the
  // time since, from the least delayed of the recent snapshots.
  double server_tick(time_point now) const;
  // The newest tick whose input is due to be sent by `now`.
  std::uint64_t send_up_to(time_point now) const;
  // When send_up_to() next grows (at most one tick period after `now`).
  time_point next_send_time(time_point now) const;

  // The lead in ticks, rounded up: inputs name the server's tick plus this.
  std::uint32_t delay() const;
  // How far ahead of the server's tick inputs are sent (half a round trip less than
  // ahead of the tick last seen).
  std::chrono::nanoseconds lead() const;
  std::chrono::nanoseconds period() const { return period_; }
  // The least round trip of the last two seconds, once one was measured.
  std::optional<std::chrono::nanoseconds> round_trip() const;
  // How many times the lead grew and shrank.
  std::uint64_t raises() const { return raises_; }
  std::uint64_t lowers() const { return lowers_; }

 private:
  struct Trip {
    time_point received;
    std::chrono::nanoseconds round_trip;
  };
  std::chrono::nanoseconds one_way() const;
  std::chrono::nanoseconds max_ahead() const;
  // How far ahead of the tick last seen inputs are sent: a round trip and a margin.
  std::chrono::nanoseconds ahead() const;
  double seen_tick(time_point now) const;
  double send_position(time_point now) const;

  InputClockConfig config_;
  std::chrono::nanoseconds period_;
  std::optional<std::uint64_t> base_tick_;  // the first tick seen: offsets count from it
  // When tick base_tick_ was seen, of the least delayed snapshots (see on_tick_seen).
  std::optional<std::chrono::nanoseconds> offset_;
  std::deque<Trip> trips_;  // the last ten seconds of round trips
  std::optional<std::uint64_t> waiting_at_;
  // Inputs are sent this far ahead of the tick seen (adaptive; see ahead()). Kept
  // against the tick seen, not the server's, so that a round trip that changes moves
  // it only through the margins, never twice.
  std::chrono::nanoseconds ahead_{0};
  bool lead_chosen_ = false;
  // Raising waits a round trip after the last raise: the margins reported meanwhile
  // are of inputs sent before it.
  time_point raise_settles_{};
  // Lowering looks at the least margin since the window began.
  time_point lower_window_start_{};
  std::optional<std::chrono::nanoseconds> least_in_window_;
  std::uint64_t raises_ = 0;
  std::uint64_t lowers_ = 0;
};

}  // namespace client
