#pragma once
// physics-netbench --prediction: the thin client and the predicting client side by
// side, each a group of bots through the same conditioned path (one-way latency,
// jitter; seeded, physics_testing::LinkConditioner) to a fixed-rate server, on each
// scene: how soon a player's own input is shown, what the rollbacks cost (their
// rate, the ticks stepped again, the CPU time of each rendered frame), the largest
// correction before and after smoothing, and the bytes each client receives.
#include <string>
#include <vector>

#include "scene/scene.h"

namespace netbench {

struct PredictionScene {
  std::string label;  // as given on the command line
  scene::SceneDef scene;
};

struct PredictionBenchOptions {
  std::vector<PredictionScene> scenes;
  int bots = 4;             // players
  int predicting_bots = 1;  // of them, in the predicting row
  int one_way_ms = 50;
  int jitter_ms = 10;
  std::uint64_t seed = 1;
  int input_change_ms = 500;  // each bot holds its input this long
  double settle_seconds = 1.0;
  double seconds = 10.0;  // measured per row
  double tick_rate = 60.0;
  std::string csv_path;
};

int run_prediction_bench(const PredictionBenchOptions& options);

}  // namespace netbench
