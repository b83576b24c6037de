#include "client/load.h"

#include <algorithm>
#include <barrier>
#include <cmath>
#include <deque>
#include <mutex>
#include <thread>

namespace client {
namespace {

using Clock = std::chrono::steady_clock;

struct BotResult {
  bool connected = false;
  std::string failure;
  std::vector<double> latencies_ms;
  std::uint64_t bytes = 0;
  std::uint64_t snapshots = 0;
  std::uint64_t records = 0;
  std::uint64_t inputs = 0;
  std::uint64_t unanswered = 0;
  std::uint64_t dropped = 0;
  double seconds = 0.0;
};

struct PendingInput {
  std::uint64_t tick;
  Clock::time_point sent_at;
};

// One bot: connects, waits for the others, then answers every snapshot with an
// input until the measurement ends.
void run_bot(const LoadConfig& config, int index, std::barrier<>& start, BotResult& result) {
  ClientConfig client_config = config.client;
  client_config.name.append("-").append(std::to_string(index));
  Client bot(client_config);
  result.connected = bot.connect(config.connect_timeout);
  if (!result.connected) result.failure = bot.last_error().to_string();
  start.arrive_and_wait();
  if (!result.connected) return;

  for (const auto settled = Clock::now() + config.settle; Clock::now() < settled;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(settled - Clock::now());
    bot.next_snapshot(std::max(left, std::chrono::milliseconds(1)));
    if (bot.state() != ConnectionState::Connected) break;
  }
  const auto begin = Clock::now();
  const auto end = begin + config.duration;
  const std::uint64_t bytes_before = bot.stats().bytes_received;
  const std::uint64_t snapshots_before = bot.stats().snapshots_received;
  const std::uint64_t records_before = bot.stats().records_received;
  std::deque<PendingInput> pending;
  std::uint64_t last_input_tick = 0;
  // Bots circle at different phases so that they do not all push the same way.
  const double phase = 2.0 * M_PI * index / std::max(1, config.bots);
  while (Clock::now() < end) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now());
    auto snapshot = bot.next_snapshot(std::max(left, std::chrono::milliseconds(1)));
    if (!snapshot) {
      if (bot.state() != ConnectionState::Connected) {
        result.failure = bot.last_error().to_string();
      }
      if (bot.state() != ConnectionState::Connected || Clock::now() >= end) break;
      continue;
    }
    while (!pending.empty() && snapshot->has_applied_input &&
           snapshot->last_applied_input_tick >= pending.front().tick) {
      const std::chrono::duration<double, std::milli> latency =
          snapshot->received_at - pending.front().sent_at;
      result.latencies_ms.push_back(latency.count());
      pending.pop_front();
    }
    if (config.still) continue;
    const std::uint64_t tick = snapshot->tick + config.input_lead;
    if (tick <= last_input_tick) continue;  // already sent (we were behind)
    const double angle = phase + 2.0 * M_PI * static_cast<double>(tick % 120) / 120.0;
    const auto sent_at = Clock::now();
    if (!bot.send_input(tick, config.acceleration * std::cos(angle),
                        config.acceleration * std::sin(angle))) {
      result.failure = bot.last_error().to_string();
      break;
    }
    pending.push_back({tick, sent_at});
    last_input_tick = tick;
    ++result.inputs;
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - begin).count();
  result.bytes = bot.stats().bytes_received - bytes_before;
  result.snapshots = bot.stats().snapshots_received - snapshots_before;
  result.records = bot.stats().records_received - records_before;
  result.dropped = bot.stats().snapshots_dropped;
  result.unanswered = pending.size();
  bot.disconnect("load run finished");
}

}  // namespace

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
      threads.emplace_back(run_bot, std::cref(config), i, std::ref(start),
                           std::ref(results[static_cast<std::size_t>(i)]));
    }
  }

  LoadReport report;
  report.bots_requested = bots;
  std::vector<double> latencies;
  std::vector<double> rates;
  double snapshot_rate_sum = 0.0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const BotResult& result = results[i];
    if (!result.failure.empty()) {
      report.failures.push_back("bot " + std::to_string(i) + ": " + result.failure);
    }
    if (!result.connected) continue;
    ++report.bots_connected;
    latencies.insert(latencies.end(), result.latencies_ms.begin(), result.latencies_ms.end());
    if (result.seconds > 0.0) {
      rates.push_back(static_cast<double>(result.bytes) / result.seconds);
      snapshot_rate_sum += static_cast<double>(result.snapshots) / result.seconds;
    }
    report.seconds = std::max(report.seconds, result.seconds);
    report.inputs_sent += result.inputs;
    report.inputs_unanswered += result.unanswered;
    report.snapshots_dropped += result.dropped;
    report.records += result.records;
    report.snapshots += result.snapshots;
    report.bytes += result.bytes;
  }
  report.latency_samples = latencies.size();
  report.latency_median_ms = quantile(latencies, 0.5);
  report.latency_p99_ms = quantile(latencies, 0.99);
  report.latency_max_ms = quantile(latencies, 1.0);
  if (!rates.empty()) {
    double sum = 0.0;
    for (double rate : rates) sum += rate;
    report.bytes_per_second_mean = sum / static_cast<double>(rates.size());
    report.bytes_per_second_min = *std::min_element(rates.begin(), rates.end());
    report.bytes_per_second_max = *std::max_element(rates.begin(), rates.end());
    report.snapshots_per_second_mean = snapshot_rate_sum / static_cast<double>(rates.size());
  }
  return report;
}

}  // namespace client
