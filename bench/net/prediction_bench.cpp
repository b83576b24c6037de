#include "prediction_bench.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <thread>

#include "client/load.h"
#include "csv_out.h"
#include "physics_testing/in_process_server.h"
#include "physics_testing/link_conditioner.h"

namespace netbench {
namespace {

using namespace std::chrono_literals;

struct Row {
  std::string client;  // "thin" or "predicting"
  std::string scene;
  client::LoadReport report;
};

client::LoadConfig bots_config(const PredictionBenchOptions& options, std::uint16_t port,
                               bool predict, int bots) {
  client::LoadConfig load;
  load.client.port = port;
  load.client.name = predict ? "netbench-predicting" : "netbench-thin";
  // The predicting client is sent the world in its Welcome: about 300 bytes a body.
  if (predict) load.client.max_message_bytes = std::size_t{64} << 20;
  load.bots = bots;
  load.predict = predict;
  load.input_change_interval = std::chrono::milliseconds(options.input_change_ms);
  load.settle = std::chrono::milliseconds(static_cast<long>(options.settle_seconds * 1000.0));
  load.duration = std::chrono::milliseconds(static_cast<long>(options.seconds * 1000.0));
  // Each predicting bot builds a world of thousands of bodies from its Welcome.
  load.connect_timeout = 60s;
  return load;
}

Row run_row(const PredictionBenchOptions& options, const PredictionScene& scene, bool predict) {
  server::ServerConfig config = physics_testing::test_server_config(false);
  config.tick_rate = options.tick_rate;
  physics_testing::InProcessServer server(scene.scene, config);
  physics_testing::PathConfig path = physics_testing::symmetric_path(
      std::chrono::milliseconds(options.one_way_ms), std::chrono::milliseconds(options.jitter_ms));
  path.seed = options.seed;
  physics_testing::LinkConditioner link(physics_testing::relay_to(server.port(), path));

  Row row;
  row.client = predict ? "predicting" : "thin";
  row.scene = scene.scene.name;
  const int measured = predict ? std::min(options.predicting_bots, options.bots) : options.bots;
  // The other players, thin, in step with the measured ones.
  std::optional<std::thread> others;
  if (measured < options.bots) {
    others.emplace([&] {
      client::run_load(bots_config(options, link.port(), false, options.bots - measured));
    });
  }
  row.report = client::run_load(bots_config(options, link.port(), predict, measured));
  if (others) others->join();
  return row;
}

// A figure the thin client does not have is "-" in the table and empty in the CSV.
std::string cell(bool has, double value, const char* format_spec) {
  return has ? fmt::format(fmt::runtime(format_spec), value) : std::string("-");
}

void print_row(const Row& row, std::FILE* csv) {
  const client::LoadReport& r = row.report;
  const bool p = r.predicting;
  const double kbit = 8.0 * r.bytes_per_second_mean / 1000.0;
  fmt::print(
      "| {} | {} | {} ({}) | {:.1f} | {:.1f} | {} | {} | {} | {} | {} | {} | {:.2f} |\n",
      row.client, row.scene, r.bots_requested, r.bots_connected, r.own_input_visible_ms_median,
      r.own_input_visible_ms_p99, cell(p, r.rollbacks_per_second, "{:.2f}"),
      cell(p, r.resimulated_ticks_per_second, "{:.1f}"), cell(p, r.frame_cpu_ms_median, "{:.3f}"),
      cell(p, r.frame_cpu_ms_p99, "{:.3f}"), cell(p, r.largest_correction_m, "{:.4f}"),
      cell(p, r.largest_smoothed_correction_m, "{:.4f}"), kbit);
  std::fflush(stdout);
  fmt::print(stderr,
             "  {} {}: {} bots joined, {:.1f} s, input->snapshot median {:.1f} ms, {} frames, "
             "desyncs {}, full states {}, {:.1f} snapshots/s\n",
             row.client, row.scene, r.bots_connected, r.seconds, r.latency_median_ms, r.frames,
             r.desyncs, r.resyncs, r.snapshots_per_second_mean);
  for (const std::string& failure : r.failures) fmt::print(stderr, "  {}\n", failure);
  if (csv == nullptr) return;
  const auto opt = [&](double value, const char* format_spec) {
    return p ? fmt::format(fmt::runtime(format_spec), value) : std::string();
  };
  fmt::print(csv, "{},{},{},{},{:.3f},{:.3f},{:.3f},{},{},{},{},{},{},{:.3f},{},{}\n", row.client,
             row.scene, r.bots_requested, r.bots_connected, r.own_input_visible_ms_median,
             r.own_input_visible_ms_p99, r.latency_median_ms, opt(r.rollbacks_per_second, "{:.3f}"),
             opt(r.resimulated_ticks_per_second, "{:.2f}"), opt(r.frame_cpu_ms_median, "{:.4f}"),
             opt(r.frame_cpu_ms_p99, "{:.4f}"), opt(r.largest_correction_m, "{:.6f}"),
             opt(r.largest_smoothed_correction_m, "{:.6f}"), kbit,
             p ? std::to_string(r.desyncs) : "", r.frames);
  std::fflush(csv);
}

}  // namespace

int run_prediction_bench(const PredictionBenchOptions& options) {
  const CsvOut out =
      open_csv(options.csv_path,
               "client,scene,bots_asked,bots_joined,own_input_visible_ms_median,"
               "own_input_visible_ms_p99,input_to_snapshot_ms_median,rollbacks_per_s,"
               "resimulated_ticks_per_s,frame_cpu_ms_median,frame_cpu_ms_p99,"
               "largest_correction_m,largest_smoothed_correction_m,kbit_per_s_per_client,"
               "desyncs,frames\n");
  if (!out.ok) return 2;
  std::FILE* csv = out.file;
  fmt::print(
      "Thin and predicting clients, {} players each changing input every {} ms ({} of them "
      "predicting in the predicting rows), {} Hz fixed rate, {} ms one way + 0-{} ms jitter "
      "(seed {}), {:.0f} s measured\n\n",
      options.bots, options.input_change_ms, std::min(options.predicting_bots, options.bots),
      options.tick_rate, options.one_way_ms, options.jitter_ms, options.seed, options.seconds);
  fmt::print(
      "| client | scene | bots (joined) | own input shown median ms | p99 ms | rollbacks/s | "
      "ticks re-simulated/s | frame CPU median ms | p99 ms | largest correction m | after "
      "smoothing m a tick | kbit/s per client |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const PredictionScene& scene : options.scenes) {
    for (const bool predict : {false, true}) print_row(run_row(options, scene, predict), csv);
  }
  if (csv != nullptr) std::fclose(csv);
  return 0;
}

}  // namespace netbench
