#include "physics/settings.h"

#include <cmath>

namespace phys {

const char* to_string(Integrator integrator) {
  switch (integrator) {
    case Integrator::ExplicitEuler:
      return "explicit-euler";
    case Integrator::SemiImplicitEuler:
      return "semi-implicit-euler";
    case Integrator::Exact:
      return "exact";
  }
  return "unknown";
}

const char* describe(SettingsError error) {
  switch (error) {
    case SettingsError::None:
      return "ok";
    case SettingsError::BadGravity:
      return "gravity must be finite, at most 1e6 m/s^2 on each axis";
    case SettingsError::BadSubsteps:
      return "substeps must be in [1, 64]";
    case SettingsError::BadSlop:
      return "slop must be a finite number in [0, 0.1]";
    case SettingsError::BadIterations:
      return "iterations must be in [1, 64]";
    case SettingsError::BadSpeedLimit:
      return "max_speed, max_acceleration and max_body_size must be finite numbers > 0";
    case SettingsError::BadSleep:
      return "sleep_speed and sleep_time must be finite numbers >= 0";
    case SettingsError::BadBounds:
      return "bounds must be finite with min < max";
  }
  return "unknown error";
}

SettingsError check_settings(const WorldSettings& s) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!is_finite(s.gravity) || std::fabs(s.gravity.x) > kMaxGravity ||
      std::fabs(s.gravity.y) > kMaxGravity) {
    return SettingsError::BadGravity;
  }
  if (s.substeps < 1 || s.substeps > 64) return SettingsError::BadSubsteps;
  if (!std::isfinite(s.slop) || s.slop < 0.0 || s.slop > 0.1) return SettingsError::BadSlop;
  if (s.position_iterations < 1 || s.position_iterations > 64 || s.velocity_iterations < 1 ||
      s.velocity_iterations > 64) {
    return SettingsError::BadIterations;
  }
  if (!positive(s.max_speed) || !positive(s.max_acceleration) || !positive(s.max_body_size) ||
      !std::isfinite(s.rest_speed) || s.rest_speed < 0.0) {
    return SettingsError::BadSpeedLimit;
  }
  if (!std::isfinite(s.sleep_speed) || s.sleep_speed < 0.0 || !std::isfinite(s.sleep_time) ||
      s.sleep_time < 0.0) {
    return SettingsError::BadSleep;
  }
  if (s.has_bounds && (!is_finite(s.bounds.min) || !is_finite(s.bounds.max) ||
                       !(s.bounds.min.x < s.bounds.max.x) || !(s.bounds.min.y < s.bounds.max.y))) {
    return SettingsError::BadBounds;
  }
  return SettingsError::None;
}

}  // namespace phys
