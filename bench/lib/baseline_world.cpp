// The baseline core behind baseline_bridge.h. Compiled with the baseline's own include
// directories and phys=phys_baseline, like the baseline's sources: every "phys" below
// is the baseline's namespace, and no header of ours is in reach.
#include <stdexcept>
#include <string>

#include "baseline_bridge.h"
#include "physics/world.h"

namespace bench::baseline {
namespace {

phys::Vec2 vec(Pair p) { return {p.x, p.y}; }
Pair pair(phys::Vec2 v) { return {v.x, v.y}; }

phys::Integrator integrator_named(const std::string& name) {
  for (phys::Integrator integrator :
       {phys::Integrator::ExplicitEuler, phys::Integrator::SemiImplicitEuler,
        phys::Integrator::Exact}) {
    if (name == phys::to_string(integrator)) return integrator;
  }
  throw std::runtime_error("baseline core: no integrator named '" + name + "'");
}

phys::WorldSettings settings_from(const SettingsInit& init) {
  phys::WorldSettings settings;
  settings.gravity = vec(init.gravity);
  settings.integrator = integrator_named(init.integrator);
  settings.substeps = init.substeps;
  settings.position_iterations = init.position_iterations;
  settings.velocity_iterations = init.velocity_iterations;
  settings.sleeping = init.sleeping;
  settings.profile = init.profile;
  const phys::SettingsError error = phys::check_settings(settings);
  if (error != phys::SettingsError::None) {
    throw std::runtime_error(std::string("baseline core: bad world settings: ") +
                             phys::describe(error));
  }
  return settings;
}

// The phases and counters by the names the bridge knows. A revision whose profile
// has other buckets gives its total only; one that renamed the restitution passes
// to velocity solves gives those.
template <typename P>
Profile profile_of(const P& p) {
  Profile out;
  out.total = p.total;
  if constexpr (requires {
                  p.order_and_integrate + p.candidates + p.moves + p.position_passes +
                      p.contact_events + p.velocity_solver + p.bounds_and_sleep;
                }) {
    out.integrate = p.order_and_integrate;
    out.broadphase = p.candidates;
    out.moves = p.moves;
    out.narrowphase = p.position_passes;
    out.contact_events = p.contact_events;
    out.resolve = p.velocity_solver;
    out.sleep = p.bounds_and_sleep;
  } else if constexpr (requires {
                         p.integrate + p.broadphase + p.narrowphase + p.resolve + p.sleep;
                       }) {
    out.integrate = p.integrate;
    out.broadphase = p.broadphase;
    out.narrowphase = p.narrowphase;
    out.resolve = p.resolve;
    out.sleep = p.sleep;
  }
  return out;
}

template <typename C>
std::uint64_t restitution_passes(const C& c) {
  if constexpr (requires { c.restitution_passes; }) {
    return c.restitution_passes;
  } else if constexpr (requires { c.velocity_solves; }) {
    return c.velocity_solves;
  } else {
    return 0;
  }
}

phys::BodyDef body_def(const BodyInit& init) {
  phys::BodyDef def;
  def.shape = init.circle ? phys::Shape::Circle : phys::Shape::Box;
  def.motion = init.is_static ? phys::Motion::Static : phys::Motion::Dynamic;
  def.position = vec(init.position);
  def.velocity = vec(init.velocity);
  def.acceleration = vec(init.acceleration);
  def.radius = init.radius;
  def.half_extents = vec(init.half_extents);
  def.mass = init.mass;
  def.restitution = init.restitution;
  def.friction = vec(init.friction);
  def.contact_friction = init.contact_friction;
  return def;
}

class BaselineWorld final : public World {
 public:
  BaselineWorld(const SettingsInit& settings, const std::vector<BodyInit>& bodies)
      : world_(settings_from(settings)) {
    for (const BodyInit& init : bodies) {
      phys::BodyDefError error = phys::BodyDefError::None;
      const phys::BodyId id = world_.add_body(body_def(init), &error);
      if (!id.is_valid()) {
        throw std::runtime_error("baseline core: body refused: " +
                                 std::string(phys::describe(error)));
      }
      if (!init.is_static) dynamic_ids_.push_back(id);
    }
  }

  void step(double dt, Profile& profile) override {
    world_.step(dt);
    profile = profile_of(world_.last_profile());
  }

  void sample(std::vector<State>& out) const override {
    out.clear();
    out.reserve(dynamic_ids_.size());
    for (const phys::BodyId id : dynamic_ids_) {
      const auto state = world_.body(id);
      out.push_back({pair(state->position), pair(state->velocity)});
    }
  }

  std::size_t awake_count() const override { return world_.awake_body_count(); }

  std::uint64_t state_hash() const override { return world_.state_hash(); }

  Counters counters() const override {
    const phys::StageCounters& c = world_.counters();
    return {c.gravity_passes,      c.friction_passes,  restitution_passes(c),     c.box_box_tests,
            c.circle_circle_tests, c.circle_box_tests, c.sleeping_bodies_skipped, c.swept_hits};
  }

 private:
  phys::World world_;
  std::vector<phys::BodyId> dynamic_ids_;
};

}  // namespace

std::unique_ptr<World> make_world(const SettingsInit& settings,
                                  const std::vector<BodyInit>& bodies) {
  return std::make_unique<BaselineWorld>(settings, bodies);
}

}  // namespace bench::baseline
