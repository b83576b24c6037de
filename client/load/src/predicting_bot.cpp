// A bot that predicts: a PredictingClient sending the same circling inputs as the
// thin bot, measuring how soon each input is shown, and what the rollbacks cost:
// their number, and the CPU time of each rendered frame.
#include <algorithm>
#include <deque>
#include <optional>

#include "bot.h"
#include "client/predicting_client.h"

namespace client {

void run_predicting_bot(const LoadConfig& config, int index, std::barrier<>& start,
                        BotResult& result) {
  PredictingClientConfig predicting;
  predicting.client = config.client;
  predicting.client.name.append("-").append(std::to_string(index));
  predicting.pacer = config.pacer;
  predicting.prediction = config.prediction;
  if (config.make_rules) predicting.rules = config.make_rules();
  PredictingClient bot(predicting);
  result.connected = bot.connect(config.connect_timeout);
  if (!result.connected) result.failure = bot.error();
  start.arrive_and_wait();
  if (!result.connected) return;

  std::deque<PendingInput> shown;           // waiting to be stepped by the prediction
  std::deque<PendingInput> confirmed;       // waiting for a snapshot that covers them
  std::deque<PendingInput> messages_shown;  // game messages waiting to be in a shown state
  GameMessageSender messages(config.messages);
  bool measuring = false;
  const GameMessageSender::Send send = [&](std::uint64_t tick, const std::string& payload) {
    return bot.send_game_message(tick, payload);
  };
  const InputPacer::InputFor input = [&](std::uint64_t tick) -> Vec2 {
    if (messages.before_input(send, tick, Clock::now()) > 0 && measuring) {
      messages_shown.push_back({tick, Clock::now()});
    }
    if (measuring) {
      shown.push_back({tick, Clock::now()});
      confirmed.push_back(shown.back());
      ++result.inputs;
    }
    return bot_acceleration(config, index, tick, bot.welcome().tick_rate);
  };

  for (const auto settled = Clock::now() + config.settle; Clock::now() < settled;) {
    if (bot.poll(settled, input) == PollResult::Ended) break;
  }
  measuring = true;
  const auto begin = Clock::now();
  const auto end = begin + config.duration;
  const PredictingStats before = bot.stats();
  std::optional<std::uint64_t> first_tick;
  std::uint64_t last_tick = 0;
  Clock::time_point first_at{};
  Clock::time_point last_at{};
  // A frame is drawn every tick period, as a game draws at its display's rate: its
  // CPU time is everything this thread did since the previous frame (the polls'
  // reads and decoding, the prediction, the rollbacks) and the render state.
  const auto frame_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / bot.welcome().tick_rate));
  auto next_frame = begin + frame_period;
  double frame_cpu_start = thread_cpu_ms();
  while (Clock::now() < end) {
    const PollResult polled = bot.poll(std::min(end, next_frame), input);
    result.game_messages_received += bot.connection().take_game_messages().size();
    if (polled == PollResult::Ended) {
      result.failure = bot.error();
      break;
    }
    // The state shown now is the prediction at predicted_tick().
    const auto now = Clock::now();
    if (now >= next_frame) {
      [[maybe_unused]] const RenderState drawn = bot.render();
      const double cpu = thread_cpu_ms();
      result.frame_cpu_ms.push_back(cpu - frame_cpu_start);
      frame_cpu_start = cpu;
      // A frame late by more than a period is not drawn twice to catch up.
      next_frame += frame_period;
      if (next_frame <= now) next_frame = now + frame_period;
    }
    const std::uint64_t predicted = bot.core().predicted_tick();
    while (!shown.empty() && predicted >= shown.front().tick) {
      result.visible_ms.push_back(
          std::chrono::duration<double, std::milli>(now - shown.front().sent_at).count());
      shown.pop_front();
    }
    // A message's effect is in the prediction when the rules run in it; otherwise only
    // in the confirmed state, once the server's effects of its tick arrived.
    const std::uint64_t holds_messages_to =
        bot.core().runs_rules() ? predicted : bot.core().confirmed_tick();
    while (!messages_shown.empty() && holds_messages_to >= messages_shown.front().tick) {
      result.message_visible_ms.push_back(
          std::chrono::duration<double, std::milli>(now - messages_shown.front().sent_at).count());
      messages_shown.pop_front();
    }
    if (polled != PollResult::Snapshot) continue;
    const Snapshot& snapshot = *bot.last_snapshot();
    if (!first_tick) {
      first_tick = snapshot.tick;
      first_at = snapshot.received_at;
    }
    last_tick = std::max(last_tick, snapshot.tick);
    last_at = snapshot.received_at;
    if (const InputPacer* pacer = bot.pacer()) result.delays.push_back(pacer->clock().delay());
    while (!confirmed.empty() && snapshot.has_applied_input &&
           snapshot.last_applied_input_tick >= confirmed.front().tick) {
      result.latencies_ms.push_back(std::chrono::duration<double, std::milli>(
                                        snapshot.received_at - confirmed.front().sent_at)
                                        .count());
      confirmed.pop_front();
    }
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - begin).count();
  if (first_tick && last_at > first_at) {
    result.ticks_per_second = static_cast<double>(last_tick - *first_tick) /
                              std::chrono::duration<double>(last_at - first_at).count();
  }
  const PredictingStats after = bot.stats();
  if (const InputPacer* pacer = bot.pacer()) {
    result.final_delay = pacer->clock().delay();
    result.margins = pacer->stats().margins_seen;
    result.late_margins = pacer->stats().late_margins;
  }
  result.bytes = after.bytes_received - before.bytes_received;
  result.snapshots = after.snapshots - before.snapshots;
  result.dropped = bot.connection().stats().snapshots_dropped;
  result.unanswered = confirmed.size();
  result.rollbacks = after.prediction.rollbacks - before.prediction.rollbacks;
  result.resimulated = after.prediction.resimulated_ticks - before.prediction.resimulated_ticks;
  result.largest_correction = after.prediction.largest_correction;
  result.largest_smoothed_correction = after.prediction.largest_smoothed_correction;
  result.desyncs = after.prediction.desyncs;
  result.resyncs = after.prediction.resyncs;
  result.game_messages_received += bot.connection().take_game_messages().size();
  result.game_messages_sent = messages.sent();
  result.rules_predicted = bot.core().runs_rules();
  bot.disconnect("load run finished");
}

}  // namespace client
