#pragma once
// Runs a scene headless for a number of fixed steps and sums up what happened.
// The world is stepped with a fixed dt; the clock is read only to time the run.
#include <cstdint>
#include <functional>

#include "scene/scene.h"

namespace sim {

struct RunOptions {
  std::uint64_t steps = 600;
  double dt = 1.0 / 60.0;            // the fixed step, seconds
  std::uint64_t progress_every = 0;  // 0: no progress reports
};

// The world after `step` steps, and the wall time spent stepping so far.
struct Progress {
  std::uint64_t step = 0;
  std::uint64_t state_hash = 0;
  std::size_t awake_bodies = 0;
  double elapsed_seconds = 0.0;
};

struct RunSummary {
  std::uint64_t steps = 0;
  std::size_t bodies = 0;
  std::size_t dynamic_bodies = 0;
  std::size_t awake_bodies = 0;  // after the last step
  double dt = 0.0;
  double total_seconds = 0.0;    // wall time spent in World::step, all steps
  std::uint64_t state_hash = 0;  // after the last step
};

// Builds the scene's world and steps it. `on_progress` is called every
// options.progress_every steps (and not at all when that is 0).
RunSummary run_scene(const scene::SceneDef& scene, const RunOptions& options,
                     const std::function<void(const Progress&)>& on_progress = {});

}  // namespace sim
