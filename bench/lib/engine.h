#pragma once
// One interface over the engines that run a SceneSpec: ours and, when installed,
// Box2D 2.4.1 and Chipmunk 7; and, when built with PHYSICS_BASELINE_CORE, the
// baseline: another revision's core, run with our settings (baseline_bridge.h). Bodies keep the
// scene's order; only dynamic ones are sampled.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "physics/settings.h"
#include "physics/stats.h"
#include "scene_spec.h"

namespace bench {

enum class EngineKind { Ours, Baseline, Box2D, Chipmunk };

// Ours and the baseline: the engines that take our settings (the grid of them).
bool runs_our_settings(EngineKind kind);

std::string_view to_string(EngineKind kind);
std::optional<EngineKind> engine_from_string(std::string_view name);
// Whether this build links the engine (the peers are optional at configure time).
bool engine_available(EngineKind kind);

struct BodySample {
  phys::Vec2 position;
  phys::Vec2 velocity;
};

class Engine {
 public:
  virtual ~Engine() = default;
  // Advances one step of dt, applying every body's constant acceleration.
  virtual void step(double dt) = 0;
  // Positions and velocities of the scene's dynamic bodies, in scene order.
  virtual void sample(std::vector<BodySample>& out) const = 0;
  virtual std::size_t awake_count() const = 0;
  // The solver iterations as the engine names them ("4", "8v/3p").
  virtual std::string iterations_label() const = 0;
  // Only ours and the baseline have these; peers return nullptr.
  virtual const phys::StepProfile* last_profile() const { return nullptr; }
  virtual const phys::StageCounters* counters() const { return nullptr; }
  // The world's state hash (phys::World::state_hash): equal for two cores that step
  // bit for bit alike. Peers have none.
  virtual std::optional<std::uint64_t> state_hash() const { return std::nullopt; }
};

struct EngineOptions {
  // Ours: every setting; the baseline: the integrator, substeps, iterations and
  // profile. Gravity comes from the scene.
  phys::WorldSettings ours;
  bool sleeping = true;  // all engines
};

// nullptr when the engine is not built in.
std::unique_ptr<Engine> make_engine(EngineKind kind, const SceneSpec& scene,
                                    const EngineOptions& options);

}  // namespace bench
