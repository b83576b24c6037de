#include "client/load.h"

#include <time.h>

#include <algorithm>
#include <barrier>
#include <cmath>
#include <deque>
#include <mutex>
#include <thread>

#include "bot.h"

namespace client {

Vec2 bot_acceleration(const LoadConfig& config, int index, std::uint64_t tick, double tick_rate) {
  if (config.still) return {0.0, 0.0};
  const int bots = std::max(1, config.bots);
  const double phase = 2.0 * M_PI * index / bots;
  const auto hold = static_cast<std::uint64_t>(
      std::llround(std::chrono::duration<double>(config.input_change_interval).count() *
                   std::max(0.0, tick_rate)));
  double turns = static_cast<double>(tick % 120) / 120.0;
  if (hold > 1) {
    // The k-th change of this bot; bot i changes i/bots of an interval after bot 0.
    const std::uint64_t offset =
        hold * static_cast<std::uint64_t>(index) / static_cast<std::uint64_t>(bots);
    const std::uint64_t k = (tick + offset) / hold;
    turns = static_cast<double>(k % 8) * 3.0 / 8.0;
  }
  const double angle = phase + 2.0 * M_PI * turns;
  return {config.acceleration * std::cos(angle), config.acceleration * std::sin(angle)};
}

double thread_cpu_ms() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) * 1000.0 + static_cast<double>(now.tv_nsec) / 1.0e6;
}

void run_thin_bot(const LoadConfig& config, int index, std::barrier<>& start, BotResult& result) {
  ClientConfig client_config = config.client;
  client_config.name.append("-").append(std::to_string(index));
  Client bot(client_config);
  result.connected = bot.connect(config.connect_timeout);
  if (!result.connected) result.failure = bot.last_error().to_string();
  start.arrive_and_wait();
  if (!result.connected) return;

  InputPacer pacer(bot, config.pacer);
  GameMessageSender messages(config.messages);
  std::deque<PendingInput> pending;
  bool measuring = false;
  const InputPacer::InputFor input = [&](std::uint64_t tick) -> Vec2 {
    if (config.still) return {0.0, 0.0};
    messages.before_input(bot, tick, Clock::now());
    if (measuring) {
      pending.push_back({tick, Clock::now()});
      ++result.inputs;
    }
    return bot_acceleration(config, index, tick, bot.welcome().tick_rate);
  };
  // A still bot only watches (at a fixed rate it sends nothing; in lockstep, where
  // every tick waits for it, it sends zeros).
  const bool watch_only = config.still && !bot.welcome().lockstep;
  const auto poll = [&](Clock::time_point until) -> std::optional<Snapshot> {
    if (!watch_only) return pacer.poll(until, input);
    return bot.next_snapshot(std::chrono::ceil<std::chrono::milliseconds>(
        std::max<Clock::duration>(until - Clock::now(), Clock::duration::zero())));
  };

  for (const auto settled = Clock::now() + config.settle; Clock::now() < settled;) {
    poll(settled);
    if (bot.state() != ConnectionState::Connected) break;
  }
  measuring = true;
  const auto begin = Clock::now();
  const auto end = begin + config.duration;
  const std::uint64_t bytes_before = bot.stats().bytes_received;
  const std::uint64_t snapshots_before = bot.stats().snapshots_received;
  const std::uint64_t records_before = bot.stats().records_received;
  const PacerStats pacer_before = pacer.stats();
  std::optional<std::uint64_t> first_tick;
  std::uint64_t last_tick = 0;
  Clock::time_point first_at{};
  Clock::time_point last_at{};
  std::optional<Snapshot> previous;
  while (Clock::now() < end) {
    auto snapshot = poll(end);
    result.game_messages_received += bot.take_game_messages().size();
    if (!snapshot) {
      if (bot.state() != ConnectionState::Connected) {
        result.failure = bot.last_error().to_string();
        break;
      }
      continue;
    }
    if (!first_tick) {
      first_tick = snapshot->tick;
      first_at = snapshot->received_at;
    }
    last_tick = std::max(last_tick, snapshot->tick);
    last_at = snapshot->received_at;
    if (previous && !watch_only) {
      // The previous snapshot's age just before this one replaced it.
      const double ahead =
          pacer.clock().server_tick(snapshot->received_at) - static_cast<double>(previous->tick);
      result.ages_ms.push_back(
          ahead * std::chrono::duration<double, std::milli>(pacer.clock().period()).count());
    }
    if (!watch_only) result.delays.push_back(pacer.clock().delay());
    while (!pending.empty() && snapshot->has_applied_input &&
           snapshot->last_applied_input_tick >= pending.front().tick) {
      const std::chrono::duration<double, std::milli> latency =
          snapshot->received_at - pending.front().sent_at;
      result.latencies_ms.push_back(latency.count());
      result.visible_ms.push_back(latency.count());
      pending.pop_front();
    }
    previous = std::move(snapshot);
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - begin).count();
  if (first_tick && last_at > first_at) {
    result.ticks_per_second = static_cast<double>(last_tick - *first_tick) /
                              std::chrono::duration<double>(last_at - first_at).count();
  }
  result.final_delay = pacer.clock().delay();
  result.margins = pacer.stats().margins_seen - pacer_before.margins_seen;
  result.late_margins = pacer.stats().late_margins - pacer_before.late_margins;
  result.bytes = bot.stats().bytes_received - bytes_before;
  result.snapshots = bot.stats().snapshots_received - snapshots_before;
  result.records = bot.stats().records_received - records_before;
  result.dropped = bot.stats().snapshots_dropped;
  result.unanswered = pending.size();
  result.game_messages_received += bot.take_game_messages().size();
  result.game_messages_sent = messages.sent();
  bot.disconnect("load run finished");
}

double quantile(std::vector<double> samples, double p) {
  if (samples.empty()) return 0.0;
  std::sort(samples.begin(), samples.end());
  const double rank = std::ceil(p * static_cast<double>(samples.size()));
  const auto index = static_cast<std::size_t>(std::max(1.0, rank)) - 1;
  return samples[std::min(index, samples.size() - 1)];
}

LoadReport run_load(const LoadConfig& config) {
  const int bots = std::max(1, config.bots);
  std::vector<BotResult> results(static_cast<std::size_t>(bots));
  std::barrier<> start(bots);
  {
    std::vector<std::jthread> threads;
    threads.reserve(results.size());
    for (int i = 0; i < bots; ++i) {
      threads.emplace_back(config.predict ? run_predicting_bot : run_thin_bot, std::cref(config), i,
                           std::ref(start), std::ref(results[static_cast<std::size_t>(i)]));
    }
  }

  LoadReport report;
  report.bots_requested = bots;
  std::vector<double> latencies;
  std::vector<double> rates;
  std::vector<double> delays;
  std::vector<double> ages;
  std::vector<double> visible;
  std::vector<double> message_visible;
  std::vector<double> frame_cpu;
  double rollback_rate_sum = 0.0;
  double resimulated_rate_sum = 0.0;
  double snapshot_rate_sum = 0.0;
  double tick_rate_sum = 0.0;
  bool any_delay = false;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const BotResult& result = results[i];
    if (!result.failure.empty()) {
      report.failures.push_back("bot " + std::to_string(i) + ": " + result.failure);
    }
    if (!result.connected) continue;
    ++report.bots_connected;
    latencies.insert(latencies.end(), result.latencies_ms.begin(), result.latencies_ms.end());
    visible.insert(visible.end(), result.visible_ms.begin(), result.visible_ms.end());
    message_visible.insert(message_visible.end(), result.message_visible_ms.begin(),
                           result.message_visible_ms.end());
    report.rules_predicted = report.rules_predicted || result.rules_predicted;
    frame_cpu.insert(frame_cpu.end(), result.frame_cpu_ms.begin(), result.frame_cpu_ms.end());
    report.largest_correction_m = std::max(report.largest_correction_m, result.largest_correction);
    report.largest_smoothed_correction_m =
        std::max(report.largest_smoothed_correction_m, result.largest_smoothed_correction);
    report.desyncs += result.desyncs;
    report.resyncs += result.resyncs;
    if (result.seconds > 0.0) {
      rollback_rate_sum += static_cast<double>(result.rollbacks) / result.seconds;
      resimulated_rate_sum += static_cast<double>(result.resimulated) / result.seconds;
      rates.push_back(static_cast<double>(result.bytes) / result.seconds);
      snapshot_rate_sum += static_cast<double>(result.snapshots) / result.seconds;
    }
    report.seconds = std::max(report.seconds, result.seconds);
    delays.insert(delays.end(), result.delays.begin(), result.delays.end());
    ages.insert(ages.end(), result.ages_ms.begin(), result.ages_ms.end());
    tick_rate_sum += result.ticks_per_second;
    report.input_delay_min =
        any_delay ? std::min(report.input_delay_min, result.final_delay) : result.final_delay;
    report.input_delay_max = std::max(report.input_delay_max, result.final_delay);
    any_delay = true;
    report.margins += result.margins;
    report.late_margins += result.late_margins;
    report.inputs_sent += result.inputs;
    report.inputs_unanswered += result.unanswered;
    report.snapshots_dropped += result.dropped;
    report.records += result.records;
    report.snapshots += result.snapshots;
    report.bytes += result.bytes;
    report.game_messages_sent += result.game_messages_sent;
    report.game_messages_received += result.game_messages_received;
  }
  report.latency_samples = latencies.size();
  report.latency_median_ms = quantile(latencies, 0.5);
  report.latency_p99_ms = quantile(latencies, 0.99);
  report.latency_max_ms = quantile(latencies, 1.0);
  report.input_delay_median = quantile(delays, 0.5);
  report.predicting = config.predict;
  report.own_input_visible_ms_median = quantile(visible, 0.5);
  report.own_input_visible_ms_p99 = quantile(visible, 0.99);
  report.own_message_visible_ms_median = quantile(message_visible, 0.5);
  report.own_message_visible_ms_p99 = quantile(message_visible, 0.99);
  report.frames = frame_cpu.size();
  report.frame_cpu_ms_median = quantile(frame_cpu, 0.5);
  report.frame_cpu_ms_p99 = quantile(frame_cpu, 0.99);
  report.snapshot_age_median_ms = quantile(ages, 0.5);
  report.snapshot_age_p99_ms = quantile(ages, 0.99);
  if (report.bots_connected > 0) {
    report.ticks_per_second = tick_rate_sum / static_cast<double>(report.bots_connected);
  }
  if (!rates.empty()) {
    double sum = 0.0;
    for (double rate : rates) sum += rate;
    report.bytes_per_second_mean = sum / static_cast<double>(rates.size());
    report.bytes_per_second_min = *std::min_element(rates.begin(), rates.end());
    report.bytes_per_second_max = *std::max_element(rates.begin(), rates.end());
    report.snapshots_per_second_mean = snapshot_rate_sum / static_cast<double>(rates.size());
    report.rollbacks_per_second = rollback_rate_sum / static_cast<double>(rates.size());
    report.resimulated_ticks_per_second = resimulated_rate_sum / static_cast<double>(rates.size());
  }
  return report;
}

}  // namespace client
