// Our world behind the bench's Engine interface.
#include <stdexcept>
#include <string>

#include "peer_engines.h"
#include "physics/world.h"

namespace bench {

namespace {

class OursEngine final : public Engine {
 public:
  OursEngine(const SceneSpec& scene, const EngineOptions& options)
      : world_(settings_for(scene, options)) {
    for (const BodySpec& spec : scene.bodies) {
      phys::BodyDefError error = phys::BodyDefError::None;
      const phys::BodyId id = world_.add_body(to_body_def(spec), &error);
      if (!id.is_valid()) {
        throw std::runtime_error("scene " + scene.name +
                                 ": body refused: " + std::string(phys::describe(error)));
      }
      if (!spec.is_static) dynamic_ids_.push_back(id);
    }
  }

  void step(double dt) override { world_.step(dt); }

  void sample(std::vector<BodySample>& out) const override {
    out.clear();
    out.reserve(dynamic_ids_.size());
    for (const phys::BodyId id : dynamic_ids_) {
      const auto state = world_.body(id);
      out.push_back({state->position, state->velocity});
    }
  }

  std::size_t awake_count() const override { return world_.awake_body_count(); }

  std::string iterations_label() const override {
    // As Box2D's are named: velocity, then position.
    return std::to_string(world_.settings().velocity_iterations) + "v/" +
           std::to_string(world_.settings().position_iterations) + "p";
  }

  const phys::StepProfile* last_profile() const override { return &world_.last_profile(); }
  const phys::StageCounters* counters() const override { return &world_.counters(); }
  std::optional<std::uint64_t> state_hash() const override { return world_.state_hash(); }

 private:
  static phys::WorldSettings settings_for(const SceneSpec& scene, const EngineOptions& options) {
    phys::WorldSettings settings = options.ours;
    settings.gravity = scene.gravity;
    settings.sleeping = options.sleeping;
    const phys::SettingsError error = phys::check_settings(settings);
    if (error != phys::SettingsError::None) {
      throw std::runtime_error(std::string("bad world settings: ") + phys::describe(error));
    }
    return settings;
  }

  phys::World world_;
  std::vector<phys::BodyId> dynamic_ids_;
};

}  // namespace

std::unique_ptr<Engine> make_ours_engine(const SceneSpec& scene, const EngineOptions& options) {
  return std::make_unique<OursEngine>(scene, options);
}

}  // namespace bench
