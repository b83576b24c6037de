#pragma once
// Runs scenes on engines over a grid of settings, one row per run.
#include <memory>
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
  bool relaxed_position_passes = phys::WorldSettings{}.relaxed_position_passes;
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
  // Ours: WorldSettings::relaxed_position_passes for every run.
  bool relaxed_position_passes = phys::WorldSettings{}.relaxed_position_passes;
  int timeline_steps = 60;  // steps per window of RunRow::timeline
  // 0: each run after the other. N: the runs of a scene take turns of N steps.
  int interleave_steps = 0;
};

// One run being stepped, which can stop and go on (for runs that take turns).
class RunInProgress {
 public:
  RunInProgress(const SceneEntry& entry, const SceneSpec& scene, EngineKind engine,
                const OursSetting& setting, bool sleeping, int timeline_steps);

  // Up to `steps` more steps, fewer at the scene's end.
  void advance(int steps);
  bool done() const { return steps_done_ >= scene_.steps; }
  // The row, with its times and error measures. Once, when done.
  RunRow finish();

 private:
  const SceneSpec& scene_;
  int timeline_steps_;
  std::unique_ptr<Engine> engine_;
  std::unique_ptr<Observer> observer_;
  RunRow row_;
  int steps_done_ = 0;
  std::vector<double> seconds_;
  std::vector<double> cpu_seconds_;
  std::vector<BodySample> samples_;
  std::vector<std::size_t> awake_after_window_;
};

// Runs one scene on one engine with one setting.
RunRow run_once(const SceneEntry& entry, const SceneSpec& scene, EngineKind engine,
                const OursSetting& setting, bool sleeping, int timeline_steps);

// Runs the grid over the given scenes, handing each row to `emit` as it completes.
void run_grid(const std::vector<SceneEntry>& scenes, const Mode& mode, const GridConfig& config,
              const std::function<void(const RunRow&)>& emit);

}  // namespace bench
