#pragma once
// The named scenes physics-bench knows, with the measures that fit each.
#include <functional>
#include <string>
#include <vector>

#include "observers.h"
#include "scene_spec.h"

namespace bench {

struct Mode {
  bool quick = false;
  int rain_count = 16000;
  // Contact friction of the 16,000-circle pile's rain: one scene per coefficient.
  std::vector<double> pile_friction{0.5};
};

struct SceneEntry {
  std::string name;
  ObserverKind observer;
  // Large scenes run only the default settings unless the whole grid is asked for.
  bool large = false;
  // Scenes where sleeping changes the cost: run with sleeping on and off.
  bool sleep_matters = false;
  // Scenes the peers run by default (the lattice rain and the pyramid).
  bool peers_by_default = false;
  std::function<SceneSpec(const Mode&)> build;
};

std::vector<SceneEntry> scene_catalog(const Mode& mode);

}  // namespace bench
