// physics-netbench: the figures of docs/BENCHMARKS.md (Network) in one process. It runs
// a real server::Server on a loopback port, N bots of the client library against
// it (client::run_load, the same code as physics-client --bots), and reads the
// server's own time per tick from stats(): the mean from total_tick_seconds, the
// p99 from last_tick_seconds sampled whenever exactly one tick passed.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "client/load.h"
#include "csv_out.h"
#include "path_grid.h"
#include "prediction_bench.h"
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
  samples.dropped_snapshots = last.skipped_snapshots - first.skipped_snapshots;
  samples.late_inputs = last.late_inputs - first.late_inputs;
  return samples;
}

struct Run {
  std::string scene_label;
  scene::SceneDef scene;
};

bool parse_encoding(const std::string& name, client::Encoding& out) {
  if (name == "predicted")
    out = client::Encoding::Predicted;
  else if (name == "exact")
    out = client::Encoding::Exact;
  else if (name == "full")
    out = client::Encoding::Full;
  else if (name == "inputs")
    out = client::Encoding::Inputs;
  else
    return false;
  return true;
}

// Every pair of an input hold and a snapshot interval, holds outermost.
std::vector<std::pair<int, int>> runs_of(const std::vector<int>& change_ms,
                                         const std::vector<int>& snapshot_intervals) {
  std::vector<std::pair<int, int>> out;
  for (const int held : change_ms) {
    for (const int interval : snapshot_intervals) out.emplace_back(held, interval);
  }
  return out;
}

}  // namespace

int run_all(const std::vector<std::string>& scene_files, const std::vector<int>& bot_counts,
            const std::vector<std::string>& encodings, const std::vector<int>& change_ms,
            const std::vector<int>& snapshot_intervals, double duration, double warmup,
            double settle, double tick_rate, bool still, const std::string& csv_path);

int main(int argc, char** argv) {
  CLI::App app{
      "physics-netbench: bandwidth, bits per body, reconstruction error, server time per tick "
      "and input latency with N bots, per scene and snapshot encoding"};
  std::vector<std::string> scene_files{"default"};
  std::vector<int> bot_counts{1, 8, 32};
  std::vector<std::string> encodings{"full", "predicted", "exact"};
  double duration = 5.0;
  double warmup = 0.0;
  double settle = 0.0;
  double tick_rate = 0.0;
  bool still = false;
  std::string csv_path;
  app.add_option("--scenes", scene_files,
                 "Scene files, or 'default' for the built-in scene, one run each")
      ->capture_default_str()
      ->delimiter(',');
  app.add_option("--bots", bot_counts, "Bot counts to run, one run each")
      ->capture_default_str()
      ->delimiter(',')
      ->check(CLI::Range(1, 1000));
  app.add_option("--encodings", encodings,
                 "Snapshot encodings: full (every body, exact), "
                 "predicted (quantised against the prediction), exact (changed bodies, exact), "
                 "inputs (the input relay, no bodies: docs/PROTOCOL.md 5.12)")
      ->capture_default_str()
      ->delimiter(',')
      ->check(CLI::IsMember({"full", "predicted", "exact", "inputs"}));
  app.add_option("--duration", duration, "Seconds measured per run")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 3600.0));
  app.add_option("--warmup", warmup, "Seconds the server runs alone before the bots join")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 3600.0));
  app.add_option("--settle", settle,
                 "Seconds the bots watch after joining before the measurement starts")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 3600.0));
  app.add_option("--tick-rate", tick_rate, "Ticks per second (0: the scene's)")
      ->check(CLI::Number)
      ->check(CLI::Range(0.0, 1000.0));
  app.add_flag("--still", still, "Bots send no inputs: they watch (no latency figures)");
  std::vector<int> change_ms{0};
  app.add_option("--input-change-ms", change_ms,
                 "Each bot holds its input this long before it changes, one run each (an input "
                 "is still sent every tick; 0: a new one every tick)")
      ->capture_default_str()
      ->delimiter(',')
      ->check(CLI::Range(0, 600000));
  std::vector<int> snapshot_intervals{1};
  app.add_option("--snapshot-intervals", snapshot_intervals,
                 "The bots' view.snapshot_interval: a snapshot every N-th tick, one run each (the "
                 "input relay then carries N ticks a snapshot)")
      ->capture_default_str()
      ->delimiter(',')
      ->check(CLI::Range(1, 1000));
  app.add_option("--csv", csv_path, "Also write the table as CSV to this file");
  // The path grid (docs/BENCHMARKS.md, "Over real paths").
  bool paths = false;
  netbench::PathGridOptions grid;
  std::string fixed_scene = "scenes/moving-1000.textproto";
  app.add_flag("--paths", paths,
               "Run the path grid instead: lockstep and fixed rate through a link conditioner "
               "at each one-way latency and jitter, with the client library's defaults (inputs "
               "ahead on the client's clock) beside the snapshot-driven schedule (inputs after "
               "each snapshot, a window of 12)");
  app.add_option("--one-way-ms", grid.one_way_ms, "Path grid: one-way latencies")
      ->capture_default_str()
      ->delimiter(',')
      ->check(CLI::Range(0, 2000));
  app.add_option("--jitter-ms", grid.jitter_ms, "Path grid: jitters (0 to this, per chunk)")
      ->capture_default_str()
      ->delimiter(',')
      ->check(CLI::Range(0, 1000));
  app.add_option("--stall-ms", grid.stall_ms, "Path grid: the stall rows' stall (0: none)")
      ->capture_default_str()
      ->check(CLI::Range(0, 10000));
  app.add_option("--stall-every-ms", grid.stall_every_ms, "Path grid: one stall this often")
      ->capture_default_str()
      ->check(CLI::Range(100, 600000));
  app.add_option("--lockstep-clients", grid.lockstep_clients, "Path grid: lockstep player counts")
      ->capture_default_str()
      ->delimiter(',')
      ->check(CLI::Range(1, 64));
  app.add_option("--fixed-scene", fixed_scene, "Path grid: the fixed-rate rows' scene file")
      ->capture_default_str();
  std::vector<std::string> modes{"lockstep", "fixed"};
  app.add_option("--modes", modes, "Path grid: which rows, lockstep and/or fixed")
      ->capture_default_str()
      ->delimiter(',')
      ->check(CLI::IsMember({"lockstep", "fixed"}));
  // The predicting client beside the thin one (docs/BENCHMARKS.md, "The predicting client").
  bool prediction = false;
  netbench::PredictionBenchOptions predicting;
  std::vector<std::string> prediction_scenes{"scenes/moving-1000.textproto",
                                             "scenes/large-4000.textproto"};
  app.add_flag("--prediction", prediction,
               "Run the thin and the predicting client side by side instead: the same bots "
               "through the same conditioned path, per scene");
  app.add_option("--prediction-scenes", prediction_scenes, "--prediction: scene files")
      ->capture_default_str()
      ->delimiter(',');
  app.add_option("--prediction-bots", predicting.bots, "--prediction: players")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  app.add_option("--prediction-predicting-bots", predicting.predicting_bots,
                 "--prediction: of the players, predicting bots in the predicting rows (the "
                 "others thin); the thin rows' are all thin")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  app.add_option("--prediction-one-way-ms", predicting.one_way_ms, "--prediction: one-way latency")
      ->capture_default_str()
      ->check(CLI::Range(0, 2000));
  app.add_option("--prediction-jitter-ms", predicting.jitter_ms,
                 "--prediction: jitter (0 to this, per chunk)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  app.add_option("--prediction-input-change-ms", predicting.input_change_ms,
                 "--prediction: each bot holds its input this long")
      ->capture_default_str()
      ->check(CLI::Range(0, 600000));
  app.add_option("--seed", predicting.seed, "--prediction: the path's jitter seed")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? 0 : 2;  // bad flags: 2, as every tool of ours
  }
  spdlog::set_level(spdlog::level::err);  // the table, not the server's log
  try {
    if (prediction) {
      for (const std::string& file : prediction_scenes) {
        auto loaded = scene::load_scene_file(file);
        if (auto* error = std::get_if<scene::SceneError>(&loaded)) {
          fmt::print(stderr, "physics-netbench: {}\n", error->to_string());
          return 2;
        }
        predicting.scenes.push_back({file, std::get<scene::SceneDef>(std::move(loaded))});
      }
      predicting.seconds = duration;
      predicting.settle_seconds = settle > 0.0 ? settle : 1.0;
      predicting.tick_rate = tick_rate > 0.0 ? tick_rate : 60.0;
      predicting.csv_path = csv_path;
      return netbench::run_prediction_bench(predicting);
    }
    if (paths) {
      auto loaded = scene::load_scene_file(fixed_scene);
      if (auto* error = std::get_if<scene::SceneError>(&loaded)) {
        fmt::print(stderr, "physics-netbench: {}\n", error->to_string());
        return 2;
      }
      grid.fixed_scene = std::get<scene::SceneDef>(std::move(loaded));
      grid.fixed_scene_label = fixed_scene;
      grid.lockstep_scene = scene::default_scene();
      grid.seconds = duration;
      grid.tick_rate = tick_rate > 0.0 ? tick_rate : 60.0;
      grid.csv_path = csv_path;
      grid.lockstep = std::find(modes.begin(), modes.end(), "lockstep") != modes.end();
      grid.fixed = std::find(modes.begin(), modes.end(), "fixed") != modes.end();
      return netbench::run_path_grid(grid);
    }
    return run_all(scene_files, bot_counts, encodings, change_ms, snapshot_intervals, duration,
                   warmup, settle, tick_rate, still, csv_path);
  } catch (const std::invalid_argument& error) {
    // A setting the server refuses (a tick rate the scene cannot take, ...).
    fmt::print(stderr, "physics-netbench: {}\n", error.what());
    return 2;
  } catch (const std::exception& error) {
    fmt::print(stderr, "physics-netbench: {}\n", error.what());
    return 1;
  }
}

int run_all(const std::vector<std::string>& scene_files, const std::vector<int>& bot_counts,
            const std::vector<std::string>& encodings, const std::vector<int>& change_ms,
            const std::vector<int>& snapshot_intervals, double duration, double warmup,
            double settle, double tick_rate, bool still, const std::string& csv_path) {
  std::vector<Run> runs;
  for (const std::string& file : scene_files) {
    if (file == "default") {
      runs.push_back({"default", scene::default_scene()});
      continue;
    }
    auto loaded = scene::load_scene_file(file);
    if (auto* error = std::get_if<scene::SceneError>(&loaded)) {
      fmt::print(stderr, "physics-netbench: {}\n", error->to_string());
      return 2;
    }
    runs.push_back({file, std::get<scene::SceneDef>(std::move(loaded))});
  }
  const CsvOut out =
      open_csv(csv_path,
               "scene,encoding,still,clients_asked,clients_joined,kbit_per_s_per_client,"
               "bits_per_body_sent,bodies_per_snapshot,snapshots_per_s,worst_error_m,"
               "server_ms_per_tick_mean,server_ms_per_tick_p99,latency_median_ms,"
               "latency_p99_ms,views,input_change_ms,snapshot_interval\n");
  if (!out.ok) return 2;
  std::FILE* csv = out.file;

  fmt::print(
      "| scene | encoding | input held ms | snapshot interval | clients (joined) | kbit/s per "
      "client | bits per body sent | bodies per snapshot | snapshots/s | worst error m | server "
      "ms/tick mean | p99 | input->snapshot median ms | p99 ms |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Run& run : runs) {
    for (const std::string& encoding_name : encodings) {
      client::Encoding encoding{};
      parse_encoding(encoding_name, encoding);
      for (const int bots : bot_counts) {
        for (const auto& [held_ms, interval] : runs_of(change_ms, snapshot_intervals)) {
          server::ServerConfig config;
          config.port = 0;
          config.tick_rate = tick_rate;
          config.max_clients = std::max(64, bots + 1);
          config.max_players_per_address = 0;  // every bot connects from 127.0.0.1
          server::Server server(config, run.scene);
          std::thread server_thread([&] { server.run(); });
          if (warmup > 0.0) {
            std::this_thread::sleep_for(
                std::chrono::milliseconds(static_cast<long>(warmup * 1000.0)));
          }

          client::LoadConfig load;
          load.client.port = server.port();
          load.client.name = "netbench";
          load.client.view.encoding = encoding;
          load.client.view.snapshot_interval = static_cast<std::uint32_t>(interval);
          load.client.want_world = encoding == client::Encoding::Inputs;
          // The world's state in the Welcome: about 300 bytes a body.
          if (load.client.want_world) load.client.max_message_bytes = std::size_t{64} << 20;
          load.bots = bots;
          load.still = still;
          load.input_change_interval = std::chrono::milliseconds(held_ms);
          load.settle = std::chrono::milliseconds(static_cast<long>(settle * 1000.0));
          load.duration = std::chrono::milliseconds(static_cast<long>(duration * 1000.0));
          std::atomic<bool> done{false};
          client::LoadReport report;
          std::thread load_thread([&] {
            report = client::run_load(load);
            done = true;
          });
          const TickSamples ticks = sample_ticks(server, done);
          const server::ServerStats stats = server.stats();
          load_thread.join();
          server.stop();
          server_thread.join();

          const double mean_ms = 1000.0 * ticks.mean_seconds;
          const double p99_ms = 1000.0 * client::quantile(ticks.seconds, 0.99);
          const double kbit = 8.0 * report.bytes_per_second_mean / 1000.0;
          const double bits_per_body =
              report.records > 0
                  ? 8.0 * static_cast<double>(report.bytes) / static_cast<double>(report.records)
                  : 0.0;
          const double bodies_per_snapshot =
              report.snapshots > 0
                  ? static_cast<double>(report.records) / static_cast<double>(report.snapshots)
                  : 0.0;
          fmt::print(
              "| {} | {} | {} | {} | {} ({}) | {:.1f} | {} | {:.1f} | {:.1f} | {:.4f} | {:.3f} | "
              "{:.3f} | {} | {} |\n",
              run.scene.name, encoding_name, held_ms, interval, bots, report.bots_connected, kbit,
              // No body sent in the run: no bits per body to speak of.
              report.records > 0 ? fmt::format("{:.1f}", bits_per_body) : std::string("-"),
              bodies_per_snapshot, report.snapshots_per_second_mean, stats.max_view_error, mean_ms,
              p99_ms, still ? std::string("-") : fmt::format("{:.2f}", report.latency_median_ms),
              still ? std::string("-") : fmt::format("{:.2f}", report.latency_p99_ms));
          if (csv != nullptr) {
            fmt::print(csv,
                       "{},{},{},{},{},{:.3f},{:.2f},{:.3f},{:.2f},{:.6f},{:.4f},{:.4f},{:.3f},{:."
                       "3f},{},{},{}\n",
                       run.scene.name, encoding_name, still ? 1 : 0, bots, report.bots_connected,
                       kbit, bits_per_body, bodies_per_snapshot, report.snapshots_per_second_mean,
                       stats.max_view_error, mean_ms, p99_ms, report.latency_median_ms,
                       report.latency_p99_ms, stats.views, held_ms, interval);
          }
          std::fflush(stdout);
          fmt::print(stderr,
                     "  {} {} bots: {} connected, {} tick samples of {} ticks, {} latency samples, "
                     "dropped steps {}, skipped snapshots {}, late inputs {}, views {}\n",
                     encoding_name, bots, report.bots_connected, ticks.seconds.size(), ticks.ticks,
                     report.latency_samples, ticks.dropped_steps, ticks.dropped_snapshots,
                     ticks.late_inputs, stats.views);
          for (const auto& failure : report.failures) fmt::print(stderr, "  {}\n", failure);
        }
      }
    }
  }
  if (csv != nullptr) std::fclose(csv);
  return 0;
}
