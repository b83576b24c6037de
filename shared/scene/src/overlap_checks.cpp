// A sweep along the axis on which the bodies spread more: bodies sorted by their
// box's low edge, each compared with the ones whose boxes start before its box ends.
// Cost: a sort, plus one comparison per pair of boxes that overlap on that axis (a
// square grid of n touching bodies, about n * sqrt(n)).
#include "overlap_checks.h"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>
#include <string>

#include "physics/formulas.h"

namespace scene::detail {

namespace {

// How deep two bodies interpenetrate; 0 when apart or touching.
// Whether the core would ever push the two apart.
bool may_collide(const phys::BodyDef& a, const phys::BodyDef& b) {
  if (a.motion != phys::Motion::Dynamic && b.motion != phys::Motion::Dynamic) return false;
  return !a.is_sensor && !b.is_sensor && phys::should_collide(a.filter, b.filter);
}

double depth(const phys::BodyDef& a, const phys::BodyDef& b) {
  const phys::Vec2 ha = phys::half_size(a.shape, a.radius, a.half_extents);
  const phys::Vec2 hb = phys::half_size(b.shape, b.radius, b.half_extents);
  const phys::Aabb box_a{a.position - ha, a.position + ha};
  const phys::Aabb box_b{b.position - hb, b.position + hb};
  if (a.shape == phys::Shape::Circle && b.shape == phys::Shape::Circle) {
    const phys::Contact c = phys::collide_circles(a.position, a.radius, b.position, b.radius);
    return c.colliding ? c.penetration : 0.0;
  }
  if (a.shape == phys::Shape::Circle) {
    const phys::Contact c = phys::collide_circle_box(a.position, a.radius, box_b);
    return c.colliding ? c.penetration : 0.0;
  }
  if (b.shape == phys::Shape::Circle) {
    const phys::Contact c = phys::collide_circle_box(b.position, b.radius, box_a);
    return c.colliding ? c.penetration : 0.0;
  }
  const double x = std::min(box_a.max.x, box_b.max.x) - std::max(box_a.min.x, box_b.min.x);
  const double y = std::min(box_a.max.y, box_b.max.y) - std::max(box_a.min.y, box_b.min.y);
  return std::max(0.0, std::min(x, y));
}

const BodySource& source_of(const std::vector<BodySource>& sources, std::size_t body) {
  return *std::prev(
      std::upper_bound(sources.begin(), sources.end(), body,
                       [](std::size_t index, const BodySource& s) { return index < s.first; }));
}

// "bodies[3]", or "grids[0] (its body 7)".
std::string describe(const std::vector<BodySource>& sources, std::size_t body) {
  const BodySource& source = source_of(sources, body);
  if (!source.grid) return source.path.to_string();
  return fmt::format("{} (its body {})", source.path.to_string(), body - source.first);
}

}  // namespace

bool check_overlaps(Checker& check, const SceneDef& def, const std::vector<BodySource>& sources) {
  const std::vector<phys::BodyDef>& bodies = def.bodies;
  if (bodies.size() < 2) return true;
  // The axis with the larger spread of centres keeps fewer boxes overlapping on it.
  double low_x = bodies[0].position.x, high_x = low_x;
  double low_y = bodies[0].position.y, high_y = low_y;
  for (const phys::BodyDef& b : bodies) {
    low_x = std::min(low_x, b.position.x);
    high_x = std::max(high_x, b.position.x);
    low_y = std::min(low_y, b.position.y);
    high_y = std::max(high_y, b.position.y);
  }
  const bool along_x = high_x - low_x >= high_y - low_y;
  const auto low = [&](std::size_t i) {
    const phys::BodyDef& b = bodies[i];
    const phys::Vec2 h = phys::half_size(b.shape, b.radius, b.half_extents);
    return along_x ? b.position.x - h.x : b.position.y - h.y;
  };
  const auto high = [&](std::size_t i) {
    const phys::BodyDef& b = bodies[i];
    const phys::Vec2 h = phys::half_size(b.shape, b.radius, b.half_extents);
    return along_x ? b.position.x + h.x : b.position.y + h.y;
  };
  std::vector<std::size_t> order(bodies.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return low(a) < low(b); });

  // The first overlap the sweep meets ends it (a pile of bodies at one point costs
  // one comparison); the later body of the pair in scene order is the one at fault.
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t i = order[k];
    const double end = high(i) - kOverlapTolerance;
    for (std::size_t m = k + 1; m < order.size() && low(order[m]) < end; ++m) {
      const std::size_t j = order[m];
      if (!may_collide(bodies[i], bodies[j])) continue;
      const double d = depth(bodies[i], bodies[j]);
      if (!(d > kOverlapTolerance)) continue;
      const std::size_t earlier = std::min(i, j);
      const std::size_t later = std::max(i, j);
      const BodySource& source = source_of(sources, later);
      return check.fail(source.grid ? source.path : source.path.child("position"),
                        fmt::format("{} overlaps {} by {:.6g} m: bodies must start apart "
                                    "(touching is allowed), unless they never collide",
                                    describe(sources, later), describe(sources, earlier), d));
    }
  }
  return true;
}

}  // namespace scene::detail
