#include "overlap.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace bench {
namespace {

struct Item {
  phys::Shape shape;
  bool is_static;
  phys::Vec2 center;
  phys::Vec2 half;  // half extents of the box, or (r, r) for a circle
  double min_x() const { return center.x - half.x; }
  double max_x() const { return center.x + half.x; }
};

double circle_box_depth(const Item& circle, const Item& box) {
  const phys::Vec2 d = circle.center - box.center;
  const double r = circle.half.x;
  const phys::Vec2 outside{std::max(std::abs(d.x) - box.half.x, 0.0),
                           std::max(std::abs(d.y) - box.half.y, 0.0)};
  if (outside.x > 0.0 || outside.y > 0.0) return r - phys::length(outside);
  // Centre inside the box: the circle must travel to the nearest face and its radius.
  return r + std::min(box.half.x - std::abs(d.x), box.half.y - std::abs(d.y));
}

double depth(const Item& a, const Item& b) {
  if (a.shape == phys::Shape::Circle && b.shape == phys::Shape::Circle) {
    return a.half.x + b.half.x - phys::length(b.center - a.center);
  }
  if (a.shape == phys::Shape::Box && b.shape == phys::Shape::Box) {
    const double ox = a.half.x + b.half.x - std::abs(b.center.x - a.center.x);
    const double oy = a.half.y + b.half.y - std::abs(b.center.y - a.center.y);
    return std::min(ox, oy);
  }
  return a.shape == phys::Shape::Circle ? circle_box_depth(a, b) : circle_box_depth(b, a);
}

}  // namespace

OverlapResult max_overlap(const SceneSpec& scene, std::span<const BodySample> dynamic,
                          double report_above) {
  std::vector<Item> items;
  items.reserve(scene.bodies.size());
  std::size_t next_dynamic = 0;
  for (const BodySpec& body : scene.bodies) {
    phys::Vec2 center = body.position;
    if (!body.is_static) {
      if (next_dynamic >= dynamic.size()) break;
      center = dynamic[next_dynamic++].position;
      if (!phys::is_finite(center)) continue;
    }
    const phys::Vec2 half = phys::half_size(body.shape, body.radius, body.half_extents);
    items.push_back({body.shape, body.is_static, center, half});
  }
  std::sort(items.begin(), items.end(),
            [](const Item& a, const Item& b) { return a.min_x() < b.min_x(); });

  OverlapResult result;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Item& a = items[i];
    for (std::size_t j = i + 1; j < items.size() && items[j].min_x() <= a.max_x(); ++j) {
      const Item& b = items[j];
      if (a.is_static && b.is_static) continue;
      if (std::abs(a.center.y - b.center.y) > a.half.y + b.half.y) continue;
      const double d = depth(a, b);
      if (d > result.max_depth) result.max_depth = d;
      if (d > report_above) ++result.overlapping_pairs;
    }
  }
  return result;
}

std::size_t escaped_count(const SceneSpec& scene, std::span<const BodySample> dynamic) {
  std::size_t escaped = 0;
  const phys::Aabb& box = scene.container;
  for (const BodySample& body : dynamic) {
    if (!phys::contains(box, body.position)) ++escaped;
  }
  return escaped;
}

std::size_t non_finite_count(std::span<const BodySample> dynamic) {
  return static_cast<std::size_t>(
      std::count_if(dynamic.begin(), dynamic.end(), [](const BodySample& b) {
        return !phys::is_finite(b.position) || !phys::is_finite(b.velocity);
      }));
}

}  // namespace bench
