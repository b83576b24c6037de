#pragma once
// The limits the world holds every body to, as it adds one and as the setters
// change one (world.cpp, world_bodies.cpp).
#include <cmath>
#include <cstdint>

#include "physics/vec2.h"

namespace phys {

// Every world's outermost bounds, with or without settings.bounds: positions beyond
// this distance from the origin on either axis are refused by add_body (OutOfBounds)
// and set_position, as the scene format refuses them (scene::kMaxCoordinate). Far
// out a double still resolves about 2e-9 m, and the spread of any two bodies stays a
// finite number (the broadphase's grid needs it).
inline constexpr double kMaxCoordinate = 1.0e7;
// False for NaN too.
inline bool within_coordinate_limit(Vec2 p) {
  return std::fabs(p.x) <= kMaxCoordinate && std::fabs(p.y) <= kMaxCoordinate;
}

// v scaled down to `limit` if longer (vec2.h), counting each time it had to be.
inline Vec2 clamp_counted(Vec2 v, double limit, std::uint64_t& clamps) {
  bool clamped = false;
  const Vec2 out = clamp_length(v, limit, &clamped);
  if (clamped) ++clamps;
  return out;
}

}  // namespace phys
