#pragma once
// Questions a program asks the world between steps (World's cast_ray, cast_ray_all,
// overlap_box, overlap_circle, overlap_point, cast_circle, cast_box), and the exact
// shape tests behind them, public so that a caller can check a single body by hand.
//
// Semantics, for every query:
// - Shapes are closed: touching counts. A ray that grazes a box's edge or a circle's
//   tangent hits it; a body whose edge lies exactly on a query box's edge overlaps it.
//   "Exactly" is as the double arithmetic below computes it: a tangent that rounding
//   puts 1e-16 away is a miss, the same miss on every platform.
// - A cast goes from `origin` (a ray) or `center` (a circle or a box) along
//   `translation`: the fraction of a hit is how far along it, in [0, 1] (1 included).
// - A cast that starts touching or inside a body hits it at fraction 0, at the cast's
//   start (the ray's origin, the shape's centre), with the normal opposite the
//   translation. Box2D's ray cast ignores such a body; here it is the first hit, so
//   that a shot fired from inside a wall stops there.
// - A zero translation casts nothing: no hit (overlap_point and overlap_* answer
//   "what is here"). So does one too short for its length to be computed (its
//   squared length underflows to 0: under about 1e-154): no_translation below.
// - The normal is the body's outward surface normal where the cast meets it (unit
//   length). At the exact corner of a box, the normal of its vertical (x) face.
// - Ties are broken by body id: the closest hit is the lowest fraction, then the
//   lowest id; cast_ray_all is ordered by fraction, then id; overlaps by id.
// - A QueryFilter without a filter finds every body; with one, the bodies whose filter
//   meets it as two bodies' filters do (should_collide, physics/body.h). Sensors are
//   skipped unless include_sensors.
// - Bad input (a coordinate, radius or half extent that is NaN, infinite or beyond
//   kMaxQueryCoordinate; a negative radius or half extent; a box whose min exceeds its
//   max) is refused: no hit, no bodies, and *error says why.
//
// Cost: the world files its bodies in three uniform grids (the broadphase's), made
// again only at the first query after they changed: the awake and kinematic bodies'
// after a step or a body added, removed or moved by hand (O(awake) when the step's
// lists are current, else a walk over every body's flags too); the sleeping bodies'
// when one fell asleep, woke or was removed; the static bodies' when one was added or
// removed. A world nobody queries pays nothing. An overlap then visits the cells its
// box spans; a cast the cells along its path, chunk by chunk, and a first-hit cast
// stops at the chunk past its hit. Bodies far larger than the median (floors, walls)
// are tested by every query. Numbers: docs/BENCHMARKS.md, "Queries".
#include <cstdint>
#include <optional>
#include <string_view>

#include "physics/body.h"
#include "physics/vec2.h"

namespace phys {

// The largest coordinate, radius, half extent or translation component a query
// takes (a hundred thousand times the world's coordinate limit): far enough for any
// question about the world, near enough that squares stay finite and exact enough.
inline constexpr double kMaxQueryCoordinate = 1.0e12;

enum class QueryError : std::uint8_t {
  None,
  NonFinite,     // a NaN or infinite coordinate, translation, radius or half extent
  TooLarge,      // beyond kMaxQueryCoordinate
  NegativeSize,  // a negative radius or half extent
  InvertedBox,   // a box whose min exceeds its max on an axis
};
std::string_view describe(QueryError error);

struct QueryFilter {
  // Nothing: every body. Otherwise the bodies with should_collide(*filter, theirs).
  std::optional<Filter> filter;
  bool include_sensors = false;
};

// Where a cast meets a body: how far along the translation (0..1), the point where
// they touch, and the body's outward normal there.
struct CastHit {
  BodyId body;
  double fraction = 0.0;
  Vec2 point{};
  Vec2 normal{};
};

// A shape somewhere: a circle (radius) or an axis-aligned box (half extents). A ray is
// a circle of radius 0, a point query a circle of radius 0 that does not move.
struct PlacedShape {
  Shape shape = Shape::Circle;
  Vec2 center{};
  double radius = 0.0;
  Vec2 half_extents{};
};

// Whether the two shapes overlap, touching included: the tests the step's contacts
// use (collide_circles, collide_circle_box, boxes_intersect in physics/formulas.h).
bool shapes_overlap(const PlacedShape& a, const PlacedShape& b);
// Whether `box` (as given, corners included) overlaps the shape.
bool box_overlaps(const Aabb& box, const PlacedShape& shape);

// Where `caster`, moved along `translation`, first meets `target` (the semantics
// above; `body` left invalid). Nothing if it does not within the translation, or if
// the translation is zero.
std::optional<CastHit> cast_against(const PlacedShape& caster, Vec2 translation,
                                    const PlacedShape& target);

// Whether a cast along `translation` casts nothing (the rule above).
constexpr bool no_translation(Vec2 translation) { return dot(translation, translation) == 0.0; }

// QueryError::None if the shape and translation are a query the world answers.
QueryError check_cast(const PlacedShape& caster, Vec2 translation);
// QueryError::None if the box is one overlap_box answers.
QueryError check_box(const Aabb& box);

}  // namespace phys
