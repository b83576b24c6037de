#pragma once
// physics-netbench --paths: the network figures over conditioned paths (one-way
// latency, jitter, stalls; physics_testing::LinkConditioner), each cell run twice side
// by side: with the client library's defaults ("clock": inputs ahead of the server by
// the input delay, on the client's clock; the window grows with the round trip) and
// with the snapshot-driven schedule ("after-snapshot": the input for T+1 once the
// snapshot of T arrived; a window of 12 asked for).
#include <string>
#include <vector>

#include "scene/scene.h"

namespace netbench {

struct PathGridOptions {
  std::vector<int> one_way_ms{0, 25, 50, 100};
  std::vector<int> jitter_ms{0, 10};
  int stall_ms = 200;         // the stall rows: one of this length ...
  int stall_every_ms = 5000;  // ... this often, at stall_one_way_ms and the last jitter
  int stall_one_way_ms = 50;
  std::vector<int> lockstep_clients{2, 8};
  bool lockstep = true;  // run the lockstep rows
  bool fixed = true;     // run the fixed-rate rows
  double seconds = 5.0;  // measured per cell (stall rows: twice)
  double tick_rate = 60.0;
  scene::SceneDef lockstep_scene;  // lockstep rows
  scene::SceneDef fixed_scene;     // fixed-rate rows: one driving bot
  std::string fixed_scene_label;
  std::string csv_path;
};

int run_path_grid(const PathGridOptions& options);

}  // namespace netbench
