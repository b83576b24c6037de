#pragma once
// The way into the baseline core: another revision's server/core, built into the same
// program with its namespace renamed (phys -> phys_baseline, bench/CMakeLists.txt), so
// that physics-bench can time it against ours in turns on one scene. Plain types only:
// this header must mean the same in the translation units compiled against either
// core, which share no physics header.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace bench::baseline {

struct Pair {
  double x = 0.0;
  double y = 0.0;
};

// A BodySpec in plain numbers.
struct BodyInit {
  bool circle = false;
  bool is_static = false;
  Pair position;
  Pair velocity;
  Pair acceleration;
  double radius = 0.5;
  Pair half_extents{0.5, 0.5};
  double mass = 1.0;
  double restitution = 0.0;
  Pair friction;
  double contact_friction = 0.0;
};

// The settings the bench varies; every other one is the baseline's own default.
struct SettingsInit {
  Pair gravity{0.0, -9.81};
  std::string integrator;  // as the core names it: "exact", ...
  int substeps = 1;
  int position_iterations = 4;
  int velocity_iterations = 8;
  bool sleeping = true;
  bool profile = true;
};

// Seconds of the last step, by phase (StepProfile's fields). A core with the
// phases of today's StepProfile fills them by their names there (integrate: the
// order and the free motion; broadphase: the candidates; narrowphase: the position
// passes; resolve: the velocity solver; sleep: bounds and sleep), moves and contact
// events included; an older core, whose buckets differed, fills those it had.
struct Profile {
  double integrate = 0.0;
  double broadphase = 0.0;
  double moves = 0.0;
  double narrowphase = 0.0;
  double contact_events = 0.0;
  double resolve = 0.0;
  double sleep = 0.0;
  double total = 0.0;
};

// The StageCounters the bench reports.
struct Counters {
  std::uint64_t gravity_passes = 0;
  std::uint64_t friction_passes = 0;
  std::uint64_t restitution_passes = 0;
  std::uint64_t box_box_tests = 0;
  std::uint64_t circle_circle_tests = 0;
  std::uint64_t circle_box_tests = 0;
  std::uint64_t sleeping_bodies_skipped = 0;
  std::uint64_t swept_hits = 0;
};

struct State {
  Pair position;
  Pair velocity;
};

class World {
 public:
  virtual ~World() = default;
  // One step of dt; `profile` gets the step's phase times.
  virtual void step(double dt, Profile& profile) = 0;
  // Positions and velocities of the dynamic bodies, in the order they were given.
  virtual void sample(std::vector<State>& out) const = 0;
  virtual std::size_t awake_count() const = 0;
  virtual Counters counters() const = 0;
  virtual std::uint64_t state_hash() const = 0;
};

// Throws std::runtime_error, in the baseline core's words, when it refuses the
// settings, the integrator's name or a body.
std::unique_ptr<World> make_world(const SettingsInit& settings,
                                  const std::vector<BodyInit>& bodies);

}  // namespace bench::baseline
