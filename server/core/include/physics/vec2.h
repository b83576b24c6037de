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

// |v| without overflow: length(v) squares the components, so it is infinite once
// |v| passes about 1.3e154; here the length is taken of v / m, m the largest
// component in magnitude, whose largest component is exactly 1 (its length is in
// [1, sqrt 2]), and multiplied by m again. Infinite only if |v| is over DBL_MAX.
inline double length_without_overflow(Vec2 v) {
  const double largest = std::fmax(std::abs(v.x), std::abs(v.y));
  if (!(largest > 0.0)) return largest;  // (0, 0), or NaN
  return largest * length(Vec2{v.x / largest, v.y / largest});
}

// v scaled down to length `limit` (finite, > 0) if it is longer, its direction
// kept; *clamped (if given) says whether it was. The world's setters and its body
// definitions clamp speeds and accelerations with it.
// Along an axis the result is exactly `limit` long; otherwise within 2 ulps of it,
// and never longer as length_without_overflow measures it, so a clamped vector
// clamped again comes back unchanged (and *clamped false).
inline Vec2 clamp_length(Vec2 v, double limit, bool* clamped = nullptr) {
  if (clamped != nullptr) *clamped = false;
  if (!(length_without_overflow(v) > limit)) return v;
  if (clamped != nullptr) *clamped = true;
  const double largest = std::fmax(std::abs(v.x), std::abs(v.y));
  const Vec2 unit_box{v.x / largest, v.y / largest};
  double factor = limit / length(unit_box);
  Vec2 out = unit_box * factor;
  // Rounding may leave `out` an ulp long; one or two ulps off the factor fix that
  // (two at most, over 3 million random vectors and limits; bounded all the same).
  for (int i = 0; i < 8 && length_without_overflow(out) > limit; ++i) {
    factor = std::nextafter(factor, 0.0);
    out = unit_box * factor;
  }
  return out;
}

// An axis-aligned box given by its corners.
struct Aabb {
  Vec2 min;
  Vec2 max;
};

// The box of half size `half` around `center`: every body's box, the core's and its
// users' (a circle's half size is (radius, radius): half_size in physics/body.h).
constexpr Aabb box_around(Vec2 center, Vec2 half) { return {center - half, center + half}; }

// Whether p lies in the box, its edges included.
constexpr bool contains(const Aabb& box, Vec2 p) {
  return p.x >= box.min.x && p.x <= box.max.x && p.y >= box.min.y && p.y <= box.max.y;
}

// Whether `inner` lies wholly in `outer`, edges included.
constexpr bool contains(const Aabb& outer, const Aabb& inner) {
  return contains(outer, inner.min) && contains(outer, inner.max);
}

}  // namespace phys
