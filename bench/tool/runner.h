#pragma once
// Runs scenes on engines over a grid of settings, one row per run.
#include <ostream>
#include <string>
#include <vector>

#include "catalog.h"
#include "engine.h"
#include "observers.h"
#include "physics/settings.h"
#include "timeline.h"

namespace bench {

struct OursSetting {
  phys::Integrator integrator = phys::Integrator::Exact;
  int substeps = 1;
  int iterations = phys::WorldSettings{}.position_iterations;
  int velocity_iterations = phys::WorldSettings{}.velocity_iterations;
};

struct RunRow {
  std::string scene;
  EngineKind engine = EngineKind::Ours;
  std::string integrator;  // ours: the phys::Integrator; peers: "peer"
  int substeps = 1;
  std::string iterations;
  bool sleeping = true;
  bool default_setting = false;  // ours at the server's defaults
  std::size_t bodies = 0;
  int steps = 0;
  double ms_median = 0.0;
  double ms_mean = 0.0;
  double ms_first = Measures::kNone;  // median over the scene's first window
  double ms_last = Measures::kNone;   // median over its last window
  // Thread CPU time per step (mean), which other processes on a shared machine
  // disturb much less than wall time: the figure the ratios prefer.
  double cpu_ms_mean = 0.0;
  double cpu_ms_first = Measures::kNone;
  double cpu_ms_last = Measures::kNone;
  std::size_t awake_end = 0;
  Measures measures;
  phys::StepProfile profile_mean{};  // seconds per step, ours only
  bool has_profile = false;
  std::vector<TimelineWindow> timeline;  // the cost over simulated time
};

struct GridConfig {
  std::vector<EngineKind> engines;
  std::vector<phys::Integrator> integrators;
  std::vector<int> substeps;
  std::vector<int> iterations;  // position iterations
  std::vector<int> velocity_iterations;
  // Empty: each scene's own choice (both for scenes where sleeping matters, on
  // otherwise). Otherwise these modes for every scene.
  std::vector<bool> sleep_modes;
  bool full_grid_on_large = false;
  bool peers_on_all_scenes = false;
  int timeline_steps = 60;  // steps per window of RunRow::timeline
};

// Runs one scene on one engine with one setting.
RunRow run_once(const SceneEntry& entry, const SceneSpec& scene, EngineKind engine,
                const OursSetting& setting, bool sleeping, int timeline_steps);

// Runs the grid over the given scenes, handing each row to `emit` as it completes.
void run_grid(const std::vector<SceneEntry>& scenes, const Mode& mode, const GridConfig& config,
              const std::function<void(const RunRow&)>& emit);

}  // namespace bench
