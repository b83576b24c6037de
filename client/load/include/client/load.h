#pragma once
// Load generation: N clients ("bots") in one process, each on its own thread,
// each sending an input every tick (paced by client::InputPacer), measuring what a
// player feels: the time from an input leaving to the first snapshot that reflects
// it, how stale the newest snapshot gets, the ticks a second the server reaches, and
// the bytes per second each client receives.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "client/client.h"
#include "client/game_message_plan.h"
#include "client/input_pacer.h"
#include "client/prediction_core.h"

namespace client {

struct LoadConfig {
  ClientConfig client;  // each bot's name gets "-<index>" appended
  int bots = 1;
  // How long the measurement runs once every bot is connected.
  std::chrono::milliseconds duration{5000};
  std::chrono::milliseconds connect_timeout{5000};
  // When each bot sends its inputs: on its clock, ahead by the input delay (fixed or
  // adaptive), or after each snapshot (for comparison).
  PacerConfig pacer;
  // Acceleration magnitude of the bots' circling pattern (m/s^2).
  double acceleration = 5.0;
  // How long each bot holds an input before it changes (0: a new one every tick, the
  // circle swept in 120 ticks). Longer than a tick: each change turns the direction
  // by 3/8 of a circle, the bots' changes spread evenly over the interval. An input
  // is sent every tick all the same, the held value repeated, as a player's client
  // does.
  std::chrono::milliseconds input_change_interval{0};
  // Still bots send no inputs: they only watch (and acknowledge, and keep alive).
  bool still = false;
  // Snapshots taken for this long after connecting, before the measurement starts
  // (a still bot's own body settles in it).
  std::chrono::milliseconds settle{0};
  // Each bot a PredictingClient (client/predicting_client.h): the input relay, the
  // world run and predicted, its own inputs shown at once.
  bool predict = false;
  PredictionConfig prediction;
  // Game messages each bot sends before its inputs (physics-client --game-message).
  GameMessagePlan messages;
  // With predict: makes each bot's own copy of the game's rules, run in its
  // prediction (PredictingClientConfig::rules). Empty: no rules.
  std::function<std::shared_ptr<server::GameRules>()> make_rules;
};

struct LoadReport {
  int bots_requested = 0;
  int bots_connected = 0;
  std::vector<std::string> failures;  // one line per bot that failed, and why
  double seconds = 0.0;               // measured wall time
  // Input-to-snapshot latency over all bots: an input for tick T counts from when
  // its bytes were written to the first snapshot with has_applied_input and
  // last_applied_input_tick >= T.
  std::size_t latency_samples = 0;
  double latency_median_ms = 0.0;
  double latency_p99_ms = 0.0;
  double latency_max_ms = 0.0;
  // Bytes received per second per client (wire bytes, prefixes included).
  double bytes_per_second_mean = 0.0;
  double bytes_per_second_min = 0.0;
  double bytes_per_second_max = 0.0;
  double snapshots_per_second_mean = 0.0;
  // Body records received over all bots, and the wire bits they came in.
  std::uint64_t records = 0;
  std::uint64_t snapshots = 0;
  std::uint64_t bytes = 0;
  std::uint64_t inputs_sent = 0;
  std::uint64_t inputs_unanswered = 0;  // sent, but no snapshot reflected them by the end
  std::uint64_t snapshots_dropped = 0;  // by the clients' own buffer bound
  // The server's ticks a second, as the bots saw them advance (mean over bots).
  double ticks_per_second = 0.0;
  // The input delay in ticks the bots used (InputClock::delay()): the median of every
  // bot's samples over the run (one per snapshot; JSON input_delay_ticks_median), and
  // each bot's delay at the end of the run, the least and the largest over bots
  // (input_delay_ticks_final_min, _max). A delay that grows shows as a median below
  // the final figures.
  std::uint32_t input_delay_min = 0;
  std::uint32_t input_delay_max = 0;
  double input_delay_median = 0.0;
  // How old the newest snapshot was, at its worst, just before the next one arrived:
  // the server's tick then (estimated, InputClock) less the snapshot's, in ms.
  double snapshot_age_median_ms = 0.0;
  double snapshot_age_p99_ms = 0.0;
  // Inputs whose margin the server reported negative (they were late).
  std::uint64_t late_margins = 0;
  std::uint64_t margins = 0;
  // From an input leaving to the first state shown that reflects it, over all bots:
  // the thin client's is the latency above (the first snapshot that covers its
  // tick); the predicting client's, the first prediction stepped through its tick.
  bool predicting = false;
  double own_input_visible_ms_median = 0.0;
  double own_input_visible_ms_p99 = 0.0;
  // With --predict and game messages: from sending a message for tick T to the first
  // state shown that holds its effect: the prediction at T or later when the rules
  // run in the prediction (rules_predicted), else the confirmed state at T or later
  // (the server's effects, a round trip on).
  double own_message_visible_ms_median = 0.0;
  double own_message_visible_ms_p99 = 0.0;
  bool rules_predicted = false;
  // The predicting client's rollbacks and ticks stepped again, per second per bot
  // (means), the largest correction of a body's predicted position over all bots
  // before and after smoothing (m), and the hash mismatches and full states.
  double rollbacks_per_second = 0.0;
  double resimulated_ticks_per_second = 0.0;
  double largest_correction_m = 0.0;
  double largest_smoothed_correction_m = 0.0;
  // The predicting client's CPU time per rendered frame (a frame each tick period:
  // the client's polls, its prediction and rollbacks, and render()), on the bot's
  // thread clock (CLOCK_THREAD_CPUTIME_ID), over all bots' frames.
  std::size_t frames = 0;
  double frame_cpu_ms_median = 0.0;
  double frame_cpu_ms_p99 = 0.0;
  std::uint64_t desyncs = 0;
  std::uint64_t resyncs = 0;
  // Game messages over all bots and the whole session (settling included): sent by
  // the bots, and received from the game.
  std::uint64_t game_messages_sent = 0;
  std::uint64_t game_messages_received = 0;
};

LoadReport run_load(const LoadConfig& config);

// The p-quantile (0..1) of the samples by nearest rank; 0 when empty. Sorts a copy.
double quantile(std::vector<double> samples, double p);

}  // namespace client
