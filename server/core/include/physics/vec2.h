#pragma once
// A 2D vector of doubles. Doubles, not floats: a float has about 8 mm of
// resolution 100 km from the origin, a double about 1.5e-11 m (see docs/ACCURACY.md).
#include <cmath>

namespace phys {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;

  constexpr Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
  constexpr Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
  constexpr Vec2 operator*(double s) const { return {x * s, y * s}; }
  constexpr Vec2 operator-() const { return {-x, -y}; }
  constexpr Vec2& operator+=(Vec2 o) {
    x += o.x;
    y += o.y;
    return *this;
  }
  constexpr Vec2& operator-=(Vec2 o) {
    x -= o.x;
    y -= o.y;
    return *this;
  }
  constexpr bool operator==(const Vec2&) const = default;
};

constexpr Vec2 operator*(double s, Vec2 v) { return {v.x * s, v.y * s}; }
constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double length(Vec2 v) { return std::sqrt(dot(v, v)); }
inline bool is_finite(Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

// An axis-aligned box given by its corners.
struct Aabb {
  Vec2 min;
  Vec2 max;
};

}  // namespace phys
