// The baseline core (baseline_bridge.h) behind the bench's Engine interface, run with
// the same settings as ours, so that the two cores' times and errors compare.
#include <string>

#include "baseline_bridge.h"
#include "peer_engines.h"

namespace bench {
namespace {

baseline::Pair pair(phys::Vec2 v) { return {v.x, v.y}; }

baseline::SettingsInit settings_for(const SceneSpec& scene, const EngineOptions& options) {
  baseline::SettingsInit init;
  init.gravity = pair(scene.gravity);
  init.integrator = phys::to_string(options.ours.integrator);
  init.substeps = options.ours.substeps;
  init.position_iterations = options.ours.position_iterations;
  init.velocity_iterations = options.ours.velocity_iterations;
  init.sleeping = options.sleeping;
  init.profile = options.ours.profile;
  return init;
}

std::vector<baseline::BodyInit> bodies_of(const SceneSpec& scene) {
  std::vector<baseline::BodyInit> bodies;
  bodies.reserve(scene.bodies.size());
  for (const BodySpec& spec : scene.bodies) {
    baseline::BodyInit init;
    init.circle = spec.shape == phys::Shape::Circle;
    init.is_static = spec.is_static;
    init.position = pair(spec.position);
    init.velocity = pair(spec.velocity);
    init.acceleration = pair(spec.acceleration);
    init.radius = spec.radius;
    init.half_extents = pair(spec.half_extents);
    init.mass = spec.mass;
    init.restitution = spec.restitution;
    init.friction = pair(spec.friction);
    init.contact_friction = spec.contact_friction;
    bodies.push_back(init);
  }
  return bodies;
}

class BaselineEngine final : public Engine {
 public:
  BaselineEngine(const SceneSpec& scene, const EngineOptions& options)
      : settings_(settings_for(scene, options)),
        world_(baseline::make_world(settings_, bodies_of(scene))) {}

  void step(double dt) override {
    world_->step(dt, step_profile_);
    // The baseline core's buckets, in ours. An older core's "integrate" held the
    // moves too, and its "narrowphase" the contact events' touch tests (its moves
    // and contact events stay 0).
    profile_ = {};
    profile_.order_and_integrate = step_profile_.integrate;
    profile_.candidates = step_profile_.broadphase;
    profile_.moves = step_profile_.moves;
    profile_.position_passes = step_profile_.narrowphase;
    profile_.contact_events = step_profile_.contact_events;
    profile_.velocity_solver = step_profile_.resolve;
    profile_.bounds_and_sleep = step_profile_.sleep;
    profile_.total = step_profile_.total;
  }

  void sample(std::vector<BodySample>& out) const override {
    world_->sample(states_);
    out.clear();
    out.reserve(states_.size());
    for (const baseline::State& s : states_) {
      out.push_back({{s.position.x, s.position.y}, {s.velocity.x, s.velocity.y}});
    }
  }

  std::size_t awake_count() const override { return world_->awake_count(); }

  std::string iterations_label() const override {
    return std::to_string(settings_.velocity_iterations) + "v/" +
           std::to_string(settings_.position_iterations) + "p";
  }

  const phys::StepProfile* last_profile() const override { return &profile_; }

  std::optional<std::uint64_t> state_hash() const override { return world_->state_hash(); }

  const phys::StageCounters* counters() const override {
    const baseline::Counters c = world_->counters();
    counters_ = {};
    counters_.gravity_passes = c.gravity_passes;
    counters_.friction_passes = c.friction_passes;
    counters_.velocity_solves = c.restitution_passes;
    counters_.box_box_tests = c.box_box_tests;
    counters_.circle_circle_tests = c.circle_circle_tests;
    counters_.circle_box_tests = c.circle_box_tests;
    counters_.sleeping_bodies_skipped = c.sleeping_bodies_skipped;
    counters_.swept_hits = c.swept_hits;
    return &counters_;
  }

 private:
  baseline::SettingsInit settings_;
  std::unique_ptr<baseline::World> world_;
  baseline::Profile step_profile_;
  phys::StepProfile profile_{};
  mutable std::vector<baseline::State> states_;
  mutable phys::StageCounters counters_{};
};

}  // namespace

std::unique_ptr<Engine> make_baseline_engine(const SceneSpec& scene, const EngineOptions& options) {
  return std::make_unique<BaselineEngine>(scene, options);
}

}  // namespace bench
