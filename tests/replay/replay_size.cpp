// physics-replay-size: how large server recordings are. Steps the default scene
// in-process with N clients whose inputs change K times a second, records each run
// (physics-server --record writes the same records) and prints one CSV row per
// run: the file's size, per tick and per second.
//   physics-replay-size [--clients 8] [--tick-rate 60] [--seconds 600] > replay-size.csv
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "server/simulation.h"
#include "server/tick_recorder.h"

namespace {

struct Run {
  double changes_per_second;
  std::uint32_t hash_every;
  std::uint32_t body_hashes_every;
};

// Client k's input during its `step`-th change: a direction that turns each time.
phys::Vec2 input_of(std::size_t k, std::uint64_t step) {
  const double phase = static_cast<double>(step) * 0.7 + static_cast<double>(k) * 1.3;
  return {20.0 * std::cos(phase), 20.0 * std::sin(phase)};
}

std::uint64_t record_run(const std::filesystem::path& path, std::size_t clients, double tick_rate,
                         std::uint64_t ticks, const Run& run) {
  server::SimulationOptions options;
  options.tick_rate = tick_rate;
  server::Simulation simulation(scene::default_scene(), options);
  server::RecordOptions record;
  record.hash_every = run.hash_every;
  record.body_hashes_every = run.body_hashes_every;
  std::string error;
  auto recorder = server::TickRecorder::create(path, simulation.scene(), simulation.tick_rate(),
                                               simulation.max_ticks_ahead(), record, &error);
  if (!recorder) throw std::runtime_error(error);
  simulation.record_to(std::move(recorder));
  for (std::size_t k = 0; k < clients; ++k) {
    if (!simulation.join(static_cast<server::ClientId>(k + 1))) {
      throw std::runtime_error("no spawn position for client " + std::to_string(k + 1));
    }
  }
  for (std::uint64_t t = 1; t <= ticks; ++t) {
    // Clients send every tick (as physics-client does); the input changes
    // changes_per_second times a second, so most sends repeat the last value.
    const auto step = static_cast<std::uint64_t>(
        std::floor(static_cast<double>(t) * run.changes_per_second / tick_rate));
    for (std::size_t k = 0; k < clients; ++k) {
      simulation.submit_input(static_cast<server::ClientId>(k + 1), t, input_of(k, step));
    }
    simulation.step_tick();
  }
  const std::uint64_t bytes = simulation.recorder()->bytes_written();
  simulation.record_to(nullptr);
  return bytes;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Measures the size of server recordings (docs/REPLAY.md)."};
  std::size_t clients = 8;
  double tick_rate = 60.0;
  double seconds = 600.0;
  std::string scratch =
      (std::filesystem::temp_directory_path() / "physics-replay-size.rec").string();
  app.add_option("--clients", clients, "Clients, each with a body")->capture_default_str();
  app.add_option("--tick-rate", tick_rate, "Ticks per second")->capture_default_str();
  app.add_option("--seconds", seconds, "Length of each recorded run")->capture_default_str();
  app.add_option("--scratch", scratch, "Where each run's recording is written")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const auto ticks = static_cast<std::uint64_t>(std::llround(seconds * tick_rate));
  const std::vector<Run> runs = {
      {60.0, 1, 60},  {10.0, 1, 60},  {2.0, 1, 60},  {10.0, 1, 0},
      {10.0, 10, 60}, {10.0, 60, 60}, {10.0, 60, 0},
  };
  fmt::print(
      "scene,clients,tick_rate,seconds,input_changes_per_second,hash_every,body_hashes_every,"
      "file_bytes,bytes_per_tick,bytes_per_second\n");
  for (const Run& run : runs) {
    const std::uint64_t bytes = record_run(scratch, clients, tick_rate, ticks, run);
    fmt::print("default,{},{},{},{},{},{},{},{:.1f},{:.0f}\n", clients, tick_rate, seconds,
               run.changes_per_second, run.hash_every, run.body_hashes_every, bytes,
               static_cast<double>(bytes) / static_cast<double>(ticks),
               static_cast<double>(bytes) / seconds);
  }
  std::filesystem::remove(scratch);
  return 0;
}
