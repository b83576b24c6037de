#pragma once
// What one bot measured, and the two kinds of bot: the thin client's (load.cpp) and
// the predicting client's (predicting_bot.cpp).
#include <barrier>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "client/load.h"

namespace client {

using Clock = std::chrono::steady_clock;

struct BotResult {
  bool connected = false;
  std::string failure;
  std::vector<double> latencies_ms;        // input to the first snapshot that covers it
  std::vector<double> visible_ms;          // input to the first state shown that reflects it
  std::vector<double> message_visible_ms;  // game message to the first state holding it
  bool rules_predicted = false;
  std::uint64_t bytes = 0;
  std::uint64_t snapshots = 0;
  std::uint64_t records = 0;
  std::uint64_t inputs = 0;
  std::uint64_t unanswered = 0;
  std::uint64_t dropped = 0;
  double seconds = 0.0;
  double ticks_per_second = 0.0;
  std::vector<double> delays;
  std::uint32_t final_delay = 0;
  std::vector<double> ages_ms;
  std::uint64_t margins = 0;
  std::uint64_t late_margins = 0;
  // The predicting client's.
  std::uint64_t rollbacks = 0;
  std::uint64_t resimulated = 0;
  double largest_correction = 0.0;
  double largest_smoothed_correction = 0.0;
  std::vector<double> frame_cpu_ms;
  std::uint64_t desyncs = 0;
  std::uint64_t resyncs = 0;
  std::uint64_t game_messages_sent = 0;
  std::uint64_t game_messages_received = 0;
};

struct PendingInput {
  std::uint64_t tick;
  Clock::time_point sent_at;
};

// The acceleration of bot `index` of `bots` at `tick` of a server at `tick_rate`: a
// circle, each bot at its own phase so that they do not all push the same way, held
// for config.input_change_interval when it is set.
Vec2 bot_acceleration(const LoadConfig& config, int index, std::uint64_t tick, double tick_rate);

// This thread's CPU time so far (CLOCK_THREAD_CPUTIME_ID), in ms.
double thread_cpu_ms();

// One bot: connects, waits at `start` for the others, then sends an input every
// tick until the measurement ends.
void run_thin_bot(const LoadConfig& config, int index, std::barrier<>& start, BotResult& result);
void run_predicting_bot(const LoadConfig& config, int index, std::barrier<>& start,
                        BotResult& result);

}  // namespace client
