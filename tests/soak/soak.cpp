// physics-soak: a long networked run checked end to end. An in-process server on a
// scene (moving-1000 by default) with 64 client slots, at a fixed rate or in
// lockstep; a seeded RNG picks, every quarter second, one slot to leave (and join
// again later) or to stop reading for a while. The server records the run; at the
// end the recording is replayed in-process and every state hash any client received
// must equal the replay's for that tick. It also reports every session end by
// reason, the process's resident memory after warm-up, the server's own structure
// sizes and its tick time against the tick budget.
//
// Exit: 0 all checks passed, 1 a desync or an unexplained drop, 2 bad flags or files.
//
// This file is the driver: the flags, the server, the run's timing and its samples
// of memory and server stats. The client fleet, the replay check and the report
// are in files of their own beside it.
#include <fmt/format.h>
#include <malloc.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <variant>

#include "client_fleet.h"
#include "replay_check.h"
#include "scene/scene.h"
#include "server/server.h"
#include "soak_options.h"
#include "soak_report.h"

namespace soak {
namespace {

using namespace std::chrono_literals;

// The process's resident set (bytes), from /proc/self/statm: server and clients.
std::uint64_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t size = 0;
  std::uint64_t resident = 0;
  statm >> size >> resident;
  return resident * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

int run(const Options& options) {
  auto loaded = scene::load_scene_file(options.scene_file);
  if (auto* error = std::get_if<scene::SceneError>(&loaded)) {
    fmt::print(stderr, "physics-soak: {}\n", error->to_string());
    return 2;
  }
  const scene::SceneDef scene = std::get<scene::SceneDef>(std::move(loaded));
  const std::filesystem::path record_path =
      options.record_path.empty()
          ? std::filesystem::temp_directory_path() / fmt::format("physics-soak-{}.rec", ::getpid())
          : std::filesystem::path(options.record_path);

  server::ServerConfig config;
  config.port = 0;
  config.lockstep = options.lockstep;
  // Realtime: a lockstep game's pace, so the tick budget means the same in both modes.
  config.lockstep_pace = server::ServerConfig::Pace::Realtime;
  config.max_clients = options.clients;
  // Every slot connects from 127.0.0.1: the per-address limits are for strangers.
  config.connects_per_second = 1000.0;
  config.connect_burst = 1000.0;
  config.max_players_per_address = 0;
  config.record_path = record_path.string();
  auto server = std::make_unique<server::Server>(config, scene);
  std::thread server_thread([&] { server->run(); });

  RunRecord record;
  record.scene_name = scene.name;
  record.tick_rate = scene.tick_rate;
  ClientFleet fleet(options, *server);
  const auto start = Clock::now();
  fleet.join_all();
  const auto end = start + std::chrono::milliseconds(static_cast<long>(options.duration * 1000));
  const auto warm = start + std::chrono::milliseconds(static_cast<long>(options.warmup * 1000));
  auto next_event = start + 250ms;
  auto next_sample = start;
  bool warmed = false;
  for (auto now = Clock::now(); now < end; now = Clock::now()) {
    fleet.pass(now);
    if (now >= next_event) {
      fleet.scripted_event(now);
      next_event += 250ms;
    }
    if (now >= next_sample) {
      const double t = std::chrono::duration<double>(now - start).count();
      record.rss.emplace_back(t, resident_bytes());
      const server::ServerStats stats = server->stats();
      record.peak_input_bytes = std::max(record.peak_input_bytes, stats.input_buffer_bytes);
      if (!warmed && now >= warm) {
        warmed = true;
        record.rss_at_warm = record.rss.back().second;
        record.at_warm = stats;
      }
      next_sample += 1s;
    }
  }
  fleet.finish();
  record.rss_end = resident_bytes();
  // What the allocator holds freed but not returned, against what is still in use.
  ::malloc_trim(0);
  record.rss_trimmed = resident_bytes();
  record.before_stop = server->stats();
  record.joined_at_stop = fleet.joined();
  server->stop();
  server_thread.join();
  record.at_end = server->stats();
  fleet.close_all();
  server.reset();  // closes the recording

  const Tally& tally = fleet.tally();
  const ReplayCheck replayed = replay_and_compare(record_path, tally.hashes);
  if (options.record_path.empty()) std::filesystem::remove(record_path);
  if (!replayed.read) {
    fmt::print(stderr, "physics-soak: the recording does not replay: {}\n", replayed.error);
    return 2;
  }
  return report(options, record, tally, replayed);
}

}  // namespace
}  // namespace soak

int main(int argc, char** argv) {
  CLI::App app{
      "physics-soak: a long run of many clients joining, leaving and reading slowly, replayed "
      "at the end: zero desyncs, no unexplained drops, memory and tick time reported"};
  soak::Options options;
  app.add_option("--scene", options.scene_file, "Scene file")->capture_default_str();
  app.add_flag("--lockstep", options.lockstep, "Lockstep (realtime pace) instead of a fixed rate");
  app.add_option("--duration", options.duration, "Seconds to run")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 86400.0));
  app.add_option("--warmup", options.warmup, "Seconds before memory growth is measured")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 86400.0));
  app.add_option("--clients", options.clients, "Client slots (and the server's max_clients)")
      ->capture_default_str()
      ->check(CLI::Range(1, 512));
  app.add_option("--seed", options.seed, "Seed of the script of joins, leaves and stalls")
      ->capture_default_str();
  std::string encoding = "predicted";
  app.add_option("--encoding", encoding, "The clients' snapshot encoding")
      ->capture_default_str()
      ->check(CLI::IsMember({"predicted", "exact", "full"}));
  app.add_option("--record", options.record_path,
                 "Keep the server's recording in this file (default: a temporary one)");
  app.add_option("--csv", options.csv_path,
                 "Append one CSV line of the figures to this file (a header first if new)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? 0 : 2;
  }
  options.encoding = encoding == "full"    ? client::Encoding::Full
                     : encoding == "exact" ? client::Encoding::Exact
                                           : client::Encoding::Predicted;
  if (options.warmup >= options.duration) {
    fmt::print(stderr, "physics-soak: --warmup must be shorter than --duration\n");
    return 2;
  }
  spdlog::set_level(spdlog::level::warn);
  try {
    return soak::run(options);
  } catch (const std::exception& error) {
    fmt::print(stderr, "physics-soak: {}\n", error.what());
    return 2;
  }
}
