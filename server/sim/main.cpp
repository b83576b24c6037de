// physics-sim: runs a scene headless for N fixed steps and prints a summary.
//   physics-sim [--scene FILE] [--steps N] [--dt S] [--every K] [--json]
//   physics-sim --replay FILE [--json]   (a server recording, docs/REPLAY.md)
// Exit codes: 0 done (a replay: every recorded hash equal), 1 a replay diverged,
// 2 bad flags, a bad scene or a bad recording.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>

#include "print_replay.h"
#include "scene/scene.h"
#include "sim_runner.h"
#include "text/json_escape.h"

namespace {

constexpr int kExitBadInput = 2;
constexpr std::int64_t kMaxSteps = 1'000'000'000;

struct Flags {
  std::string scene_file;  // empty: the built-in default scene
  // Signed on purpose: CLI11 would wrap "-3" into a huge unsigned count.
  std::int64_t steps = 600;
  std::optional<double> dt;  // default: 1 / the scene's tick rate
  std::int64_t every = 0;
  bool json = false;
  std::string replay_file;  // set: check this recording instead of running a scene
};

std::string hex(std::uint64_t hash) { return fmt::format("{:016x}", hash); }

void print_progress(const sim::Progress& progress, std::uint64_t total, bool json) {
  if (json) {
    fmt::print("{{\"step\":{},\"state_hash\":\"{}\",\"awake_bodies\":{},\"elapsed_s\":{}}}\n",
               progress.step, hex(progress.state_hash), progress.awake_bodies,
               progress.elapsed_seconds);
  } else {
    fmt::print("step {}/{}  hash {}  awake {}  elapsed {:.3f} s\n", progress.step, total,
               hex(progress.state_hash), progress.awake_bodies, progress.elapsed_seconds);
  }
  std::fflush(stdout);
}

void print_summary(const std::string& scene_name, const sim::RunSummary& summary, bool json) {
  const double per_step =
      summary.steps > 0 ? summary.total_seconds / static_cast<double>(summary.steps) : 0.0;
  if (json) {
    fmt::print(
        "{{\"scene\":\"{}\",\"steps\":{},\"dt\":{},\"bodies\":{},\"dynamic_bodies\":{},"
        "\"awake_bodies\":{},\"total_s\":{},\"per_step_s\":{},\"state_hash\":\"{}\"}}\n",
        text::json_escape(scene_name), summary.steps, summary.dt, summary.bodies,
        summary.dynamic_bodies, summary.awake_bodies, summary.total_seconds, per_step,
        hex(summary.state_hash));
    return;
  }
  fmt::print("scene          {}\n", scene_name);
  fmt::print("steps          {} (dt {} s)\n", summary.steps, summary.dt);
  fmt::print("bodies         {} ({} dynamic)\n", summary.bodies, summary.dynamic_bodies);
  fmt::print("awake bodies   {}\n", summary.awake_bodies);
  fmt::print("total time     {:.6f} s\n", summary.total_seconds);
  fmt::print("time per step  {:.3f} us\n", per_step * 1e6);
  fmt::print("state hash     {}\n", hex(summary.state_hash));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Runs a physics scene headless for N fixed steps and prints a summary."};
  Flags flags;
  app.add_option("--scene", flags.scene_file,
                 "Scene file (.textproto, docs/SCENES.md); the built-in default scene if "
                 "left out");
  app.add_option("--steps", flags.steps, "Number of fixed steps to run")
      ->check(CLI::Range(std::int64_t{0}, kMaxSteps))
      ->capture_default_str();
  app.add_option("--dt", flags.dt, "Fixed step in seconds, in (0, 1]; default 1/tick_rate");
  app.add_option("--every", flags.every, "Print a progress line every K steps (0: never)")
      ->check(CLI::Range(std::int64_t{0}, kMaxSteps))
      ->capture_default_str();
  app.add_flag("--json", flags.json, "Print JSON (one object per line) instead of text");
  app.add_option("--replay", flags.replay_file,
                 "Step a server recording (physics-server --record) again and check every "
                 "recorded hash; exits 1 at the first tick that differs")
      ->excludes("--scene", "--steps", "--dt", "--every");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  }
  if (!flags.replay_file.empty()) return sim::replay_and_print(flags.replay_file, flags.json);
  // Checked here, not with CLI11's Range: a NaN passes every comparison.
  if (flags.dt && !(std::isfinite(*flags.dt) && *flags.dt > 0.0 && *flags.dt <= 1.0)) {
    fmt::print(stderr, "--dt: must be a finite number in (0, 1], got {}\n", *flags.dt);
    return kExitBadInput;
  }

  scene::SceneDef scene;
  if (flags.scene_file.empty()) {
    scene = scene::default_scene();
  } else {
    scene::SceneResult loaded = scene::load_scene_file(flags.scene_file);
    if (const auto* error = std::get_if<scene::SceneError>(&loaded)) {
      fmt::print(stderr, "{}\n", error->to_string());
      return kExitBadInput;
    }
    scene = std::get<scene::SceneDef>(std::move(loaded));
  }

  sim::RunOptions options;
  options.steps = static_cast<std::uint64_t>(flags.steps);
  options.dt = flags.dt.value_or(scene::fixed_dt(scene));
  options.progress_every = static_cast<std::uint64_t>(flags.every);
  try {
    const sim::RunSummary summary =
        sim::run_scene(scene, options, [&](const sim::Progress& progress) {
          print_progress(progress, options.steps, flags.json);
        });
    print_summary(scene.name, summary, flags.json);
  } catch (const std::invalid_argument& e) {
    fmt::print(stderr, "{}\n", e.what());
    return kExitBadInput;
  }
  return 0;
}
