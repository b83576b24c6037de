// The exact shape tests behind the world's queries (physics/query.h): overlaps are
// the contact tests of the step; a cast is a ray against the Minkowski sum of the
// two shapes, a box grown by the sum's rounding, whose corners are circles.
#include <algorithm>
#include <cmath>

#include "physics/formulas.h"
#include "physics/query.h"

namespace phys {

namespace {

constexpr double kInf = HUGE_VAL;

Aabb box_of(const PlacedShape& s) {
  return box_around(s.center, half_size(s.shape, s.radius, s.half_extents));
}

// Where a ray meets a box around `center` of half size core + rounding whose corners
// are rounded by `rounding`: its fraction and the outward normal there.
struct Crossing {
  double fraction;
  Vec2 normal;
};

// One axis of the slab test: narrows [enter, exit] to where the ray is between lo
// and hi on this axis, and notes the axis whose entry is latest. False if the ray
// runs parallel to the axis outside the slab.
bool clip_slab(double origin, double delta, double lo, double hi, int axis, double& enter,
               double& exit, int& enter_axis) {
  if (delta == 0.0) return origin >= lo && origin <= hi;
  double near = (lo - origin) / delta;
  double far = (hi - origin) / delta;
  if (near > far) std::swap(near, far);
  if (near > enter) {  // strict: at an exact corner the x axis, tested first, stays
    enter = near;
    enter_axis = axis;
  }
  exit = std::min(exit, far);
  return true;
}

Vec2 backwards(Vec2 translation) {
  const double len = length(translation);
  return {-translation.x / len, -translation.y / len};
}

// A ray from `origin` along `translation` against a circle: Box2D's form, through the
// point of the ray nearest the centre, which keeps the square root well conditioned.
std::optional<Crossing> ray_circle(Vec2 origin, Vec2 translation, Vec2 center, double radius) {
  const double len = length(translation);
  const Vec2 unit{translation.x / len, translation.y / len};
  const double along = dot(center - origin, unit);
  const Vec2 nearest = origin + unit * along;
  const Vec2 off = center - nearest;
  const double half_chord_sq = radius * radius - dot(off, off);
  if (half_chord_sq < 0.0) return std::nullopt;
  const double half_chord = std::sqrt(half_chord_sq);
  double distance = along - half_chord;
  if (distance < 0.0) {
    if (along + half_chord < 0.0) return std::nullopt;  // behind the origin
    distance = 0.0;                                     // the origin is inside
  }
  if (distance > len) return std::nullopt;
  const double fraction = distance / len;
  if (fraction > 1.0) return std::nullopt;
  if (fraction == 0.0) return Crossing{0.0, -unit};
  const Vec2 out = origin + translation * fraction - center;
  const double out_len = length(out);
  if (!(out_len > 0.0)) return Crossing{fraction, -unit};
  return Crossing{fraction, {out.x / out_len, out.y / out_len}};
}

std::optional<Crossing> ray_rounded_box(Vec2 origin, Vec2 translation, Vec2 center, Vec2 core,
                                        double rounding) {
  const Aabb outer = box_around(center, core + Vec2{rounding, rounding});
  double enter = -kInf;
  double exit = kInf;
  int axis = -1;
  if (!clip_slab(origin.x, translation.x, outer.min.x, outer.max.x, 0, enter, exit, axis) ||
      !clip_slab(origin.y, translation.y, outer.min.y, outer.max.y, 1, enter, exit, axis)) {
    return std::nullopt;
  }
  if (enter > exit || exit < 0.0 || enter > 1.0) return std::nullopt;
  const double fraction = std::max(enter, 0.0);
  if (rounding > 0.0) {
    // In a corner's square the sum is that corner's circle.
    const Vec2 at = origin + translation * fraction;
    const Aabb inner = box_around(center, core);
    const bool beyond_x = at.x < inner.min.x || at.x > inner.max.x;
    const bool beyond_y = at.y < inner.min.y || at.y > inner.max.y;
    if (beyond_x && beyond_y) {
      const Vec2 corner{at.x < inner.min.x ? inner.min.x : inner.max.x,
                        at.y < inner.min.y ? inner.min.y : inner.max.y};
      return ray_circle(origin, translation, corner, rounding);
    }
  }
  if (enter <= 0.0) return Crossing{0.0, backwards(translation)};
  if (axis == 0) return Crossing{fraction, {translation.x > 0.0 ? -1.0 : 1.0, 0.0}};
  return Crossing{fraction, {0.0, translation.y > 0.0 ? -1.0 : 1.0}};
}

bool finite_within(double v) { return std::isfinite(v) && std::fabs(v) <= kMaxQueryCoordinate; }

QueryError check_values(std::initializer_list<double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) return QueryError::NonFinite;
  }
  for (double v : values) {
    if (!finite_within(v)) return QueryError::TooLarge;
  }
  return QueryError::None;
}

}  // namespace

std::string_view describe(QueryError error) {
  switch (error) {
    case QueryError::None:
      return "no error";
    case QueryError::NonFinite:
      return "a coordinate, translation, radius or half extent is NaN or infinite";
    case QueryError::TooLarge:
      return "a coordinate, translation, radius or half extent is beyond 1e12";
    case QueryError::NegativeSize:
      return "a radius or half extent is negative";
    case QueryError::InvertedBox:
      return "the box's min exceeds its max";
  }
  return "unknown query error";
}

bool shapes_overlap(const PlacedShape& a, const PlacedShape& b) {
  if (a.shape == Shape::Circle && b.shape == Shape::Circle) {
    return collide_circles(a.center, a.radius, b.center, b.radius).colliding;
  }
  if (a.shape == Shape::Circle) return collide_circle_box(a.center, a.radius, box_of(b)).colliding;
  if (b.shape == Shape::Circle) return collide_circle_box(b.center, b.radius, box_of(a)).colliding;
  return boxes_intersect(box_of(a), box_of(b));
}

bool box_overlaps(const Aabb& box, const PlacedShape& shape) {
  if (shape.shape == Shape::Circle) {
    return collide_circle_box(shape.center, shape.radius, box).colliding;
  }
  return boxes_intersect(box, box_of(shape));
}

std::optional<CastHit> cast_against(const PlacedShape& caster, Vec2 translation,
                                    const PlacedShape& target) {
  if (no_translation(translation)) return std::nullopt;
  if (shapes_overlap(caster, target)) {
    return CastHit{BodyId::invalid(), 0.0, caster.center, backwards(translation)};
  }
  const bool caster_round = caster.shape == Shape::Circle;
  const bool target_round = target.shape == Shape::Circle;
  // The Minkowski sum: a box of the boxes' half extents, rounded by the radii.
  const Vec2 core =
      (caster_round ? Vec2{} : caster.half_extents) + (target_round ? Vec2{} : target.half_extents);
  const double rounding =
      (caster_round ? caster.radius : 0.0) + (target_round ? target.radius : 0.0);
  const std::optional<Crossing> crossing =
      ray_rounded_box(caster.center, translation, target.center, core, rounding);
  if (!crossing) return std::nullopt;
  CastHit hit{BodyId::invalid(), crossing->fraction, {}, crossing->normal};
  const Vec2 moved = caster.center + translation * crossing->fraction;
  if (caster_round) {
    hit.point = moved - crossing->normal * caster.radius;
  } else if (target_round) {
    hit.point = target.center + crossing->normal * target.radius;
  } else {
    // Two boxes touch along a segment (or at a corner): its middle.
    const Aabb a = box_around(moved, caster.half_extents);
    const Aabb b = box_of(target);
    hit.point = {(std::max(a.min.x, b.min.x) + std::min(a.max.x, b.max.x)) * 0.5,
                 (std::max(a.min.y, b.min.y) + std::min(a.max.y, b.max.y)) * 0.5};
  }
  return hit;
}

QueryError check_cast(const PlacedShape& caster, Vec2 translation) {
  const Vec2 half = half_size(caster.shape, caster.radius, caster.half_extents);
  const QueryError values = check_values(
      {caster.center.x, caster.center.y, translation.x, translation.y, half.x, half.y});
  if (values != QueryError::None) return values;
  if (half.x < 0.0 || half.y < 0.0) return QueryError::NegativeSize;
  return QueryError::None;
}

QueryError check_box(const Aabb& box) {
  const QueryError values = check_values({box.min.x, box.min.y, box.max.x, box.max.y});
  if (values != QueryError::None) return values;
  if (box.min.x > box.max.x || box.min.y > box.max.y) return QueryError::InvertedBox;
  return QueryError::None;
}

}  // namespace phys
