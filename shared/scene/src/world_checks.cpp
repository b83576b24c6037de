// The world block's checks: gravity, tick rate, bounds, integrator, solver
// iterations, speed and sleep limits.
#include "world_checks.h"

#include <fmt/format.h>

#include <cstdint>

namespace scene::detail {

namespace proto = physics::scene;

namespace {

bool check_int_setting(Checker& check, const FieldPath& path, bool has, std::int64_t value,
                       std::int64_t low, std::int64_t high, int* out) {
  if (!has) return true;
  if (!check.in_range(path, value, low, high)) return false;
  *out = static_cast<int>(value);
  return true;
}

bool check_bounds(Checker& check, const FieldPath& path, const proto::Bounds& bounds,
                  phys::WorldSettings& settings) {
  if (!check.coordinate(path.child("min"), bounds.min()) ||
      !check.coordinate(path.child("max"), bounds.max()))
    return false;
  if (bounds.max().x() <= bounds.min().x())
    return check.fail(path.child("max").child("x"),
                      fmt::format("must be greater than world.bounds.min.x ({}), got {}",
                                  bounds.min().x(), bounds.max().x()));
  if (bounds.max().y() <= bounds.min().y())
    return check.fail(path.child("max").child("y"),
                      fmt::format("must be greater than world.bounds.min.y ({}), got {}",
                                  bounds.min().y(), bounds.max().y()));
  settings.has_bounds = true;
  settings.bounds = {to_vec(bounds.min()), to_vec(bounds.max())};
  return true;
}

bool check_integrator(Checker& check, const FieldPath& path, proto::Integrator integrator,
                      phys::WorldSettings& settings) {
  switch (integrator) {
    case proto::INTEGRATOR_UNSPECIFIED:
      break;
    case proto::INTEGRATOR_EXPLICIT_EULER:
      settings.integrator = phys::Integrator::ExplicitEuler;
      break;
    case proto::INTEGRATOR_SEMI_IMPLICIT_EULER:
      settings.integrator = phys::Integrator::SemiImplicitEuler;
      break;
    case proto::INTEGRATOR_EXACT:
      settings.integrator = phys::Integrator::Exact;
      break;
    default:
      return check.fail(path, fmt::format("unknown integrator {}", static_cast<int>(integrator)));
  }
  return true;
}

// The field a verdict of the core's check_settings is about.
const char* verdict_field(phys::SettingsError verdict) {
  const char* field = "world";
  switch (verdict) {
    case phys::SettingsError::BadGravity:
      field = "gravity";
      break;
    case phys::SettingsError::BadSubsteps:
      field = "substeps";
      break;
    case phys::SettingsError::BadSlop:
      field = "slop";
      break;
    case phys::SettingsError::BadIterations:
      field = "position_iterations";
      break;
    case phys::SettingsError::BadSpeedLimit:
      field = "max_speed";
      break;
    case phys::SettingsError::BadSleep:
      field = "sleep_speed";
      break;
    case phys::SettingsError::BadBounds:
      field = "bounds";
      break;
    case phys::SettingsError::None:
      break;
  }
  return field;
}

}  // namespace

bool check_world(Checker& check, const proto::World& world, SceneDef* def) {
  const FieldPath base = FieldPath().child("world");
  phys::WorldSettings& settings = def->world;
  if (world.has_gravity()) {
    if (!check.finite(base.child("gravity"), world.gravity())) return false;
    settings.gravity = to_vec(world.gravity());
  }
  if (world.has_tick_rate()) {
    const FieldPath path = base.child("tick_rate");
    if (!check.in_range(path, world.tick_rate(), kMinTickRate, kMaxTickRate)) return false;
    def->tick_rate = world.tick_rate();
  }
  if (world.has_steps_per_frame()) {
    if (!check.in_range(base.child("steps_per_frame"), world.steps_per_frame(), 1,
                        kMaxStepsPerFrame))
      return false;
    def->steps_per_frame = static_cast<int>(world.steps_per_frame());
  }
  if (world.has_slop()) {
    if (!check.in_range(base.child("slop"), world.slop(), 0.0, 0.1)) return false;
    settings.slop = world.slop();
  }
  if (world.has_bounds() && !check_bounds(check, base.child("bounds"), world.bounds(), settings)) {
    return false;
  }
  if (world.has_max_acceleration()) {
    const FieldPath path = base.child("max_acceleration");
    if (!check.positive(path, world.max_acceleration())) return false;
    if (!check.at_most(path, world.max_acceleration(), settings.max_acceleration,
                       "the core's acceleration limit"))
      return false;
    def->max_acceleration = world.max_acceleration();
  }
  if (!check_integrator(check, base.child("integrator"), world.integrator(), settings)) {
    return false;
  }
  if (!check_int_setting(check, base.child("substeps"), world.has_substeps(), world.substeps(), 1,
                         64, &settings.substeps) ||
      !check_int_setting(check, base.child("position_iterations"), world.has_position_iterations(),
                         world.position_iterations(), 1, 64, &settings.position_iterations) ||
      !check_int_setting(check, base.child("velocity_iterations"), world.has_velocity_iterations(),
                         world.velocity_iterations(), 1, 64, &settings.velocity_iterations))
    return false;
  if (world.has_continuous()) settings.continuous = world.continuous();
  if (world.has_sleeping()) settings.sleeping = world.sleeping();
  if (world.has_shock_propagation()) settings.shock_propagation = world.shock_propagation();
  if (world.has_hold_resting_support()) {
    settings.hold_resting_support = world.hold_resting_support();
  }
  if (world.has_rest_speed()) {
    if (!check.not_negative(base.child("rest_speed"), world.rest_speed())) return false;
    settings.rest_speed = world.rest_speed();
  }
  if (world.has_max_speed()) {
    if (!check.positive(base.child("max_speed"), world.max_speed())) return false;
    settings.max_speed = world.max_speed();
  }
  if (world.has_sleep_speed()) {
    if (!check.not_negative(base.child("sleep_speed"), world.sleep_speed())) return false;
    settings.sleep_speed = world.sleep_speed();
  }
  if (world.has_sleep_time()) {
    if (!check.not_negative(base.child("sleep_time"), world.sleep_time())) return false;
    settings.sleep_time = world.sleep_time();
  }
  // The core's own verdict, in case it is stricter than the checks above.
  const phys::SettingsError verdict = phys::check_settings(settings);
  if (verdict == phys::SettingsError::None) return true;
  return check.fail(base.child(verdict_field(verdict)), phys::describe(verdict));
}

}  // namespace scene::detail
