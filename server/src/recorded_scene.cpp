#include "server/recorded_scene.h"

#include <cmath>
#include <string>

#include "physics/fnv_hash.h"
#include "physics/formulas.h"

namespace server {
namespace {

namespace rec = physics::recording;

rec::Vec2 to_recorded(phys::Vec2 v) {
  rec::Vec2 out;
  out.set_x(v.x);
  out.set_y(v.y);
  return out;
}

phys::Vec2 from_recorded(const rec::Vec2& v) { return {v.x(), v.y()}; }

rec::Integrator to_recorded(phys::Integrator integrator) {
  switch (integrator) {
    case phys::Integrator::ExplicitEuler:
      return rec::INTEGRATOR_EXPLICIT_EULER;
    case phys::Integrator::SemiImplicitEuler:
      return rec::INTEGRATOR_SEMI_IMPLICIT_EULER;
    case phys::Integrator::Exact:
      return rec::INTEGRATOR_EXACT;
  }
  return rec::INTEGRATOR_UNSPECIFIED;
}

rec::BodyDef to_recorded(const phys::BodyDef& def) {
  rec::BodyDef out;
  out.set_shape(def.shape == phys::Shape::Circle ? rec::SHAPE_CIRCLE : rec::SHAPE_BOX);
  out.set_is_static(def.motion == phys::Motion::Static);
  *out.mutable_position() = to_recorded(def.position);
  *out.mutable_velocity() = to_recorded(def.velocity);
  *out.mutable_acceleration() = to_recorded(def.acceleration);
  out.set_radius(def.radius);
  *out.mutable_half_extents() = to_recorded(def.half_extents);
  out.set_mass(def.mass);
  out.set_restitution(def.restitution);
  *out.mutable_friction() = to_recorded(def.friction);
  out.set_contact_friction(def.contact_friction);
  out.set_is_kinematic(def.motion == phys::Motion::Kinematic);
  if (!(def.filter == phys::Filter{})) {
    out.set_category_bits(def.filter.category_bits);
    out.set_mask_bits(def.filter.mask_bits);
    out.set_group(def.filter.group);
  }
  out.set_is_sensor(def.is_sensor);
  out.set_name(def.name);
  return out;
}

bool from_recorded(const rec::BodyDef& in, phys::BodyDef& def) {
  switch (in.shape()) {
    case rec::SHAPE_CIRCLE:
      def.shape = phys::Shape::Circle;
      break;
    case rec::SHAPE_BOX:
      def.shape = phys::Shape::Box;
      break;
    default:
      return false;
  }
  if (in.is_static() && in.is_kinematic()) return false;
  def.motion = in.is_static()      ? phys::Motion::Static
               : in.is_kinematic() ? phys::Motion::Kinematic
                                   : phys::Motion::Dynamic;
  def.position = from_recorded(in.position());
  def.velocity = from_recorded(in.velocity());
  def.acceleration = from_recorded(in.acceleration());
  def.radius = in.radius();
  def.half_extents = from_recorded(in.half_extents());
  def.mass = in.mass();
  def.restitution = in.restitution();
  def.friction = from_recorded(in.friction());
  def.contact_friction = in.contact_friction();
  if (in.has_category_bits()) def.filter.category_bits = in.category_bits();
  if (in.has_mask_bits()) def.filter.mask_bits = in.mask_bits();
  def.filter.group = in.group();
  def.is_sensor = in.is_sensor();
  def.name = in.name();
  return true;
}

rec::WorldSettings to_recorded(const phys::WorldSettings& s) {
  rec::WorldSettings out;
  *out.mutable_gravity() = to_recorded(s.gravity);
  out.set_integrator(to_recorded(s.integrator));
  out.set_substeps(s.substeps);
  out.set_slop(s.slop);
  out.set_position_iterations(s.position_iterations);
  out.set_velocity_iterations(s.velocity_iterations);
  out.set_warm_starting(s.warm_starting);
  out.set_continuous(s.continuous);
  out.set_shock_propagation(s.shock_propagation);
  out.set_hold_resting_support(s.hold_resting_support);
  out.set_rest_speed(s.rest_speed);
  out.set_max_speed(s.max_speed);
  out.set_max_acceleration(s.max_acceleration);
  out.set_sleeping(s.sleeping);
  out.set_sleep_speed(s.sleep_speed);
  out.set_sleep_time(s.sleep_time);
  out.set_has_bounds(s.has_bounds);
  *out.mutable_bounds_min() = to_recorded(s.bounds.min);
  *out.mutable_bounds_max() = to_recorded(s.bounds.max);
  out.set_max_body_size(s.max_body_size);
  out.set_max_bodies(s.max_bodies);
  return out;
}

bool from_recorded(const rec::WorldSettings& in, phys::WorldSettings& s) {
  switch (in.integrator()) {
    case rec::INTEGRATOR_EXPLICIT_EULER:
      s.integrator = phys::Integrator::ExplicitEuler;
      break;
    case rec::INTEGRATOR_SEMI_IMPLICIT_EULER:
      s.integrator = phys::Integrator::SemiImplicitEuler;
      break;
    case rec::INTEGRATOR_EXACT:
      s.integrator = phys::Integrator::Exact;
      break;
    default:
      return false;
  }
  s.gravity = from_recorded(in.gravity());
  s.substeps = in.substeps();
  s.slop = in.slop();
  s.position_iterations = in.position_iterations();
  s.velocity_iterations = in.velocity_iterations();
  s.warm_starting = in.warm_starting();
  s.continuous = in.continuous();
  s.shock_propagation = in.shock_propagation();
  s.hold_resting_support = in.hold_resting_support();
  s.rest_speed = in.rest_speed();
  s.max_speed = in.max_speed();
  s.max_acceleration = in.max_acceleration();
  s.sleeping = in.sleeping();
  s.sleep_speed = in.sleep_speed();
  s.sleep_time = in.sleep_time();
  s.has_bounds = in.has_bounds();
  s.bounds.min = from_recorded(in.bounds_min());
  s.bounds.max = from_recorded(in.bounds_max());
  s.max_body_size = in.max_body_size();
  s.max_bodies = in.max_bodies();
  s.profile = false;
  return true;
}

// Finite, and within the scene format's largest |coordinate| on both axes.
bool within_coordinate_limit(phys::Vec2 p) {
  return std::fabs(p.x) <= scene::kMaxCoordinate && std::fabs(p.y) <= scene::kMaxCoordinate;
}

// The scene loader's checks of a body that the core's own (at build time) leave out:
// position within the coordinate limit, speed and acceleration within the world's,
// a static body still, and inside the bounds. "" when none fails.
std::string body_problem(const phys::BodyDef& def, const phys::WorldSettings& world) {
  if (!within_coordinate_limit(def.position))
    return "position is not finite or beyond the largest |coordinate| 1e7";
  if (!phys::is_finite(def.velocity) || !(phys::length(def.velocity) <= world.max_speed))
    return "velocity is not finite or above world.max_speed";
  if (!phys::is_finite(def.acceleration) ||
      !(phys::length(def.acceleration) <= world.max_acceleration))
    return "acceleration is not finite or above the core's acceleration limit";
  if (def.motion == phys::Motion::Static &&
      (def.velocity != phys::Vec2{} || def.acceleration != phys::Vec2{}))
    return "a static body has a velocity or an acceleration";
  if (world.has_bounds &&
      !phys::contains(
          world.bounds,
          phys::box_around(def.position, phys::half_size(def.shape, def.radius, def.half_extents))))
    return "lies outside world.bounds";
  return {};
}

}  // namespace

physics::recording::Scene to_recorded(const scene::SceneDef& scene) {
  rec::Scene out;
  out.set_name(scene.name);
  *out.mutable_world() = to_recorded(scene.world);
  out.set_tick_rate(scene.tick_rate);
  out.set_max_acceleration(scene.max_acceleration);
  out.mutable_bodies()->Reserve(static_cast<int>(scene.bodies.size()));
  for (const phys::BodyDef& body : scene.bodies) *out.add_bodies() = to_recorded(body);
  for (const phys::Vec2& point : scene.spawn_points) *out.add_spawn_points() = to_recorded(point);
  *out.mutable_player() = to_recorded(scene.player);
  return out;
}

std::variant<scene::SceneDef, std::string> from_recorded(const physics::recording::Scene& in) {
  scene::SceneDef out;
  out.name = in.name();
  if (!in.has_world()) return std::string("scene: no world settings");
  if (!from_recorded(in.world(), out.world)) return std::string("scene.world: unknown integrator");
  if (const phys::SettingsError error = phys::check_settings(out.world);
      error != phys::SettingsError::None) {
    return std::string("scene.world: ") + phys::describe(error);
  }
  out.tick_rate = in.tick_rate();
  if (std::string problem = scene::tick_rate_problem(out.tick_rate); !problem.empty()) {
    return "scene.tick_rate: " + problem;
  }
  out.max_acceleration = in.max_acceleration();
  if (!(std::isfinite(out.max_acceleration) && out.max_acceleration >= 0.0)) {
    return std::string("scene.max_acceleration: must be finite and >= 0");
  }
  // The count is checked before the bodies are copied (the parsed message already
  // holds them, bounded by the header's byte limit).
  const auto body_count = static_cast<std::int64_t>(in.bodies_size());
  if (body_count > scene::kMaxSceneBodies || body_count > out.world.max_bodies) {
    return "scene.bodies: " + std::to_string(body_count) + " bodies, over the limit";
  }
  out.bodies.resize(static_cast<std::size_t>(body_count));
  for (int i = 0; i < in.bodies_size(); ++i) {
    phys::BodyDef& body = out.bodies[static_cast<std::size_t>(i)];
    if (!from_recorded(in.bodies(i), body)) {
      return "scene.bodies[" + std::to_string(i) + "]: unknown shape";
    }
    if (std::string problem = body_problem(body, out.world); !problem.empty()) {
      return "scene.bodies[" + std::to_string(i) + "]: " + problem;
    }
  }
  if (in.spawn_points_size() == 0) return std::string("scene.spawn_points: empty");
  if (in.spawn_points_size() > scene::kMaxSceneBodies) {
    return std::string("scene.spawn_points: over the limit");
  }
  for (const rec::Vec2& point : in.spawn_points()) {
    const phys::Vec2 p = from_recorded(point);
    if (!within_coordinate_limit(p)) {
      return std::string("scene.spawn_points: not finite or beyond the largest |coordinate| 1e7");
    }
    out.spawn_points.push_back(p);
  }
  if (!in.has_player() || !from_recorded(in.player(), out.player)) {
    return std::string("scene.player: missing or of unknown shape");
  }
  return out;
}

std::uint64_t body_hash(const phys::BodyState& body) {
  phys::Fnv1a64 h;
  h.mix(body.id.packed());
  h.mix(static_cast<std::uint64_t>(body.shape) | (static_cast<std::uint64_t>(body.motion) << 8));
  h.mix_double(body.position.x);
  h.mix_double(body.position.y);
  h.mix_double(body.velocity.x);
  h.mix_double(body.velocity.y);
  h.mix_double(body.acceleration.x);
  h.mix_double(body.acceleration.y);
  h.mix_double(body.radius);
  h.mix_double(body.half_extents.x);
  h.mix_double(body.half_extents.y);
  return h.value();
}

}  // namespace server
