// World's queries (physics/query.h): the grids choose whom to test, the exact shape
// tests (query_shapes.cpp) decide, then filters and sensors, then the order by id.
#include "physics/query.h"

#include <algorithm>

#include "physics/world.h"
#include "world_impl.h"

namespace phys {

namespace {

PlacedShape shape_of(const Body& b) { return {b.shape, b.position, b.radius, b.half}; }

bool passes(const WorldImpl& w, std::uint32_t slot, const QueryFilter& query) {
  const BodyFilter& f = w.filters[slot];
  if (f.sensor && !query.include_sensors) return false;
  return !query.filter || should_collide(*query.filter, f.filter);
}

BodyId id_of(const WorldImpl& w, std::uint32_t slot) { return {slot, w.bodies[slot].generation}; }

// Lower fraction first, then lower id.
bool comes_first(const CastHit& a, const CastHit& b) {
  if (a.fraction != b.fraction) return a.fraction < b.fraction;
  return a.body.index < b.body.index;
}

bool refuse(QueryError found, QueryError* error) {
  if (error != nullptr) *error = found;
  return found != QueryError::None;
}

// The cast's hit on the body in `slot`, if it passes the filter and is hit.
std::optional<CastHit> hit_on(const WorldImpl& w, std::uint32_t slot, const PlacedShape& caster,
                              Vec2 translation, const QueryFilter& query) {
  if (!passes(w, slot, query)) return std::nullopt;
  std::optional<CastHit> hit = cast_against(caster, translation, shape_of(w.bodies[slot]));
  if (hit) hit->body = id_of(w, slot);
  return hit;
}

std::optional<CastHit> first_hit(const WorldImpl& w, const PlacedShape& caster, Vec2 translation,
                                 const QueryFilter& query) {
  if (no_translation(translation)) return std::nullopt;
  w.query_index.refresh(w.bodies, w.lists_if_current());
  std::optional<CastHit> best;
  const Vec2 reach = half_size(caster.shape, caster.radius, caster.half_extents);
  w.query_index.sweep(caster.center, translation, reach, [&](std::span<const std::uint32_t> slots) {
    for (std::uint32_t slot : slots) {
      const std::optional<CastHit> hit = hit_on(w, slot, caster, translation, query);
      if (hit && (!best || comes_first(*hit, *best))) best = hit;
    }
    return best ? best->fraction : HUGE_VAL;
  });
  return best;
}

std::vector<BodyId> overlaps(const WorldImpl& w, const Aabb& candidates_box,
                             const std::function<bool(const PlacedShape&)>& overlaps_body,
                             const QueryFilter& query) {
  w.query_index.refresh(w.bodies, w.lists_if_current());
  std::vector<std::uint32_t> slots;
  w.query_index.overlapping(candidates_box, slots);
  std::vector<BodyId> out;
  for (std::uint32_t slot : slots) {
    if (passes(w, slot, query) && overlaps_body(shape_of(w.bodies[slot]))) {
      out.push_back(id_of(w, slot));
    }
  }
  return out;
}

}  // namespace

std::optional<CastHit> World::cast_ray(Vec2 origin, Vec2 translation, const QueryFilter& filter,
                                       QueryError* error) const {
  const PlacedShape ray{Shape::Circle, origin, 0.0, {}};
  if (refuse(check_cast(ray, translation), error)) return std::nullopt;
  return first_hit(*impl_, ray, translation, filter);
}

std::vector<CastHit> World::cast_ray_all(Vec2 origin, Vec2 translation, const QueryFilter& filter,
                                         QueryError* error) const {
  const PlacedShape ray{Shape::Circle, origin, 0.0, {}};
  std::vector<CastHit> hits;
  if (refuse(check_cast(ray, translation), error)) return hits;
  if (no_translation(translation)) return hits;
  const WorldImpl& w = *impl_;
  w.query_index.refresh(w.bodies, w.lists_if_current());
  std::vector<std::uint32_t> slots;
  w.query_index.sweep(origin, translation, {}, [&slots](std::span<const std::uint32_t> chunk) {
    slots.insert(slots.end(), chunk.begin(), chunk.end());
    return HUGE_VAL;
  });
  std::sort(slots.begin(), slots.end());
  slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
  for (std::uint32_t slot : slots) {
    if (std::optional<CastHit> hit = hit_on(w, slot, ray, translation, filter)) {
      hits.push_back(*hit);
    }
  }
  std::sort(hits.begin(), hits.end(), comes_first);
  return hits;
}

std::vector<BodyId> World::overlap_box(const Aabb& box, const QueryFilter& filter,
                                       QueryError* error) const {
  if (refuse(check_box(box), error)) return {};
  return overlaps(
      *impl_, box, [&box](const PlacedShape& body) { return box_overlaps(box, body); }, filter);
}

std::vector<BodyId> World::overlap_circle(Vec2 center, double radius, const QueryFilter& filter,
                                          QueryError* error) const {
  const PlacedShape circle{Shape::Circle, center, radius, {}};
  if (refuse(check_cast(circle, {}), error)) return {};
  return overlaps(
      *impl_, box_around(center, {radius, radius}),
      [&circle](const PlacedShape& body) { return shapes_overlap(circle, body); }, filter);
}

std::vector<BodyId> World::overlap_point(Vec2 point, const QueryFilter& filter,
                                         QueryError* error) const {
  return overlap_circle(point, 0.0, filter, error);
}

std::optional<CastHit> World::cast_circle(Vec2 center, double radius, Vec2 translation,
                                          const QueryFilter& filter, QueryError* error) const {
  const PlacedShape circle{Shape::Circle, center, radius, {}};
  if (refuse(check_cast(circle, translation), error)) return std::nullopt;
  return first_hit(*impl_, circle, translation, filter);
}

std::optional<CastHit> World::cast_box(Vec2 center, Vec2 half_extents, Vec2 translation,
                                       const QueryFilter& filter, QueryError* error) const {
  const PlacedShape box{Shape::Box, center, 0.0, half_extents};
  if (refuse(check_cast(box, translation), error)) return std::nullopt;
  return first_hit(*impl_, box, translation, filter);
}

}  // namespace phys
