// physics-netbench: the figures of docs/BENCHMARKS.md (Network) in one process. It runs
// a real server::Server on a loopback port, N bots of the client library against
// it (client::run_load, the same code as physics-client --bots), and reads the
// server's own time per tick from stats(): the mean from total_tick_seconds, the
// p99 from last_tick_seconds sampled whenever exactly one tick passed.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "client/load.h"
#include "scene/scene.h"
#include "server/server.h"

namespace {

using Clock = std::chrono::steady_clock;

struct TickSamples {
  std::vector<double> seconds;  // last_tick_seconds, read each time one tick passed
  double mean_seconds = 0.0;    // exact: total_tick_seconds / ticks over the run
  double max_seconds = 0.0;
  std::uint64_t ticks = 0;
  std::uint64_t dropped_steps = 0;
  std::uint64_t dropped_snapshots = 0;
  std::uint64_t late_inputs = 0;
};

// Reads stats() until `done`; keeps last_tick_seconds whenever exactly one new tick
// has been stepped since the previous read (so the value belongs to that tick).
TickSamples sample_ticks(const server::Server& server, const std::atomic<bool>& done) {
  TickSamples samples;
  const server::ServerStats first = server.stats();
  std::uint64_t seen = first.ticks_stepped;
  while (!done.load()) {
    const server::ServerStats stats = server.stats();
    if (stats.ticks_stepped == seen + 1) samples.seconds.push_back(stats.last_tick_seconds);
    seen = stats.ticks_stepped;
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  const server::ServerStats last = server.stats();
  samples.max_seconds = last.max_tick_seconds;
  samples.ticks = last.ticks_stepped - first.ticks_stepped;
  if (samples.ticks > 0) {
    samples.mean_seconds =
        (last.total_tick_seconds - first.total_tick_seconds) / static_cast<double>(samples.ticks);
  }
  samples.dropped_steps = last.dropped_steps - first.dropped_steps;
  samples.dropped_snapshots = last.dropped_snapshots - first.dropped_snapshots;
  samples.late_inputs = last.late_inputs - first.late_inputs;
  return samples;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"physics-netbench: server time per tick, input latency and bandwidth with N bots"};
  std::string scene_file;
  std::vector<int> bot_counts{1, 8, 32};
  double duration = 5.0;
  double tick_rate = 0.0;
  app.add_option("--scene", scene_file, "Scene file (default: the built-in scene)");
  app.add_option("--bots", bot_counts, "Bot counts to run, one run each")->capture_default_str();
  app.add_option("--duration", duration, "Seconds measured per run")->capture_default_str();
  app.add_option("--tick-rate", tick_rate, "Ticks per second (0: the scene's)");
  CLI11_PARSE(app, argc, argv);

  scene::SceneDef scene = scene::default_scene();
  if (!scene_file.empty()) {
    auto loaded = scene::load_scene_file(scene_file);
    if (auto* error = std::get_if<scene::SceneError>(&loaded)) {
      fmt::print(stderr, "physics-netbench: {}\n", error->to_string());
      return 1;
    }
    scene = std::get<scene::SceneDef>(std::move(loaded));
  }

  fmt::print(
      "| scene | bodies | clients | server ms/tick mean | p99 | max | input->snapshot "
      "median ms | p99 ms | bytes/s per client | snapshots/s per client |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const int bots : bot_counts) {
    server::ServerConfig config;
    config.port = 0;
    config.tick_rate = tick_rate;
    config.max_clients = std::max(64, bots + 1);
    server::Server server(config, scene);
    std::thread server_thread([&] { server.run(); });

    client::LoadConfig load;
    load.client.port = server.port();
    load.client.name = "netbench";
    load.bots = bots;
    load.duration = std::chrono::milliseconds(static_cast<long>(duration * 1000.0));
    std::atomic<bool> done{false};
    client::LoadReport report;
    std::thread load_thread([&] {
      report = client::run_load(load);
      done = true;
    });
    const TickSamples ticks = sample_ticks(server, done);
    load_thread.join();
    server.stop();
    server_thread.join();

    const double mean_ms = 1000.0 * ticks.mean_seconds;
    fmt::print("| {} | {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.2f} | {:.2f} | {:.0f} | {:.1f} |\n",
               scene.name, scene.bodies.size() + static_cast<std::size_t>(bots), bots, mean_ms,
               1000.0 * client::quantile(ticks.seconds, 0.99), 1000.0 * ticks.max_seconds,
               report.latency_median_ms, report.latency_p99_ms, report.bytes_per_second_mean,
               report.snapshots_per_second_mean);
    fmt::print(stderr,
               "  {} bots: {} connected, {} tick samples of {} ticks, {} latency samples, "
               "dropped steps {}, dropped snapshots {}, late inputs {}, unanswered inputs {}\n",
               bots, report.bots_connected, ticks.seconds.size(), ticks.ticks,
               report.latency_samples, ticks.dropped_steps, ticks.dropped_snapshots,
               ticks.late_inputs, report.inputs_unanswered);
    for (const auto& failure : report.failures) fmt::print(stderr, "  {}\n", failure);
  }
  return 0;
}
