#pragma once
// The error measures that fit each scene, fed the sampled state during a run.
#include <limits>
#include <memory>
#include <span>
#include <string>

#include "engine.h"
#include "scene_spec.h"

namespace bench {

struct Measures {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  std::string error_name;  // the scene's main error, the y axis of the Pareto plot
  double error = kNone;
  double max_overlap = kNone;   // metres, deepest over the samples taken
  double top_drift = kNone;     // metres, top body from its start
  double energy_drift = kNone;  // relative (bounce) or joules of growth (settled pile)
  long escaped = -1;
  long non_finite = -1;
  std::string notes;  // key=value;key=value
};

class Observer {
 public:
  virtual ~Observer() = default;
  // After step `step` (1-based) of the run.
  virtual void observe(int step, std::span<const BodySample> dynamic) = 0;
  virtual Measures finish() = 0;
};

enum class ObserverKind { Trajectory, FrictionDecay, Bounce, Stack, Pile, Stages };

std::unique_ptr<Observer> make_observer(ObserverKind kind, const SceneSpec& scene);

}  // namespace bench
