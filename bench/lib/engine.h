#pragma once
// One interface over the engines that run a SceneSpec: ours and, when installed,
// Box2D 2.4.1 and Chipmunk 7. Bodies keep the scene's order; only dynamic ones are
// sampled.
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "physics/settings.h"
#include "physics/stats.h"
#include "scene_spec.h"

namespace bench {

enum class EngineKind { Ours, Box2D, Chipmunk };

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
  // Only ours has these; peers return nullptr.
  virtual const phys::StepProfile* last_profile() const { return nullptr; }
  virtual const phys::StageCounters* counters() const { return nullptr; }
};

struct EngineOptions {
  phys::WorldSettings ours;  // ours: every setting; gravity comes from the scene
  bool sleeping = true;      // all engines
};

// nullptr when the engine is not built in.
std::unique_ptr<Engine> make_engine(EngineKind kind, const SceneSpec& scene,
                                    const EngineOptions& options);

}  // namespace bench
