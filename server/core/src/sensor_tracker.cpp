#include "sensor_tracker.h"

#include <algorithm>
#include <cmath>

#include "world_impl.h"

namespace phys {

namespace {

// Whether two shapes share interior: touching edges or points do not count.
bool shapes_overlap(const Body& a, const Body& b) {
  if (a.shape == Shape::Box && b.shape == Shape::Box) {
    return std::fabs(a.position.x - b.position.x) < a.half.x + b.half.x &&
           std::fabs(a.position.y - b.position.y) < a.half.y + b.half.y;
  }
  if (a.shape == Shape::Circle && b.shape == Shape::Circle) {
    const Vec2 d = b.position - a.position;
    const double reach = a.radius + b.radius;
    return dot(d, d) < reach * reach;
  }
  const Body& circle = a.shape == Shape::Circle ? a : b;
  const Body& box = a.shape == Shape::Circle ? b : a;
  // The box's point nearest the circle's centre, inside the circle.
  const Vec2 nearest{
      std::clamp(circle.position.x, box.position.x - box.half.x, box.position.x + box.half.x),
      std::clamp(circle.position.y, box.position.y - box.half.y, box.position.y + box.half.y)};
  const Vec2 d = circle.position - nearest;
  return dot(d, d) < circle.radius * circle.radius;
}

}  // namespace

std::size_t SensorTracker::update(std::uint64_t step, const WorldImpl& world) {
  const std::vector<Body>& bodies = world.bodies;
  sensor_boxes_.clear();
  for (const std::uint32_t s : world.sensors) sensor_boxes_.push_back(bodies[s].bounds());
  visitor_boxes_.clear();
  visitor_slots_.clear();
  for (std::uint32_t i = 0; i < bodies.size(); ++i) {
    if (!bodies[i].alive || world.filters[i].sensor) continue;
    visitor_boxes_.push_back(bodies[i].bounds());
    visitor_slots_.push_back(i);
  }
  // Sensors ascend by slot, and each one's visitors by slot: next_ comes out in
  // pair order, with no sort.
  next_.clear();
  if (!sensor_boxes_.empty() && !visitor_boxes_.empty()) {
    grid_.build(visitor_boxes_);
    std::vector<std::uint32_t>& hits = overlaps_;
    for (std::size_t q = 0; q < world.sensors.size(); ++q) {
      const std::uint32_t s = world.sensors[q];
      grid_.find_overlaps(sensor_boxes_[q], hits);
      for (const std::uint32_t t : hits) {
        const std::uint32_t v = visitor_slots_[t];
        if (!should_collide(world.filters[s].filter, world.filters[v].filter)) continue;
        if (!shapes_overlap(bodies[s], bodies[v])) continue;
        next_.push_back({s, bodies[s].generation, v, bodies[v].generation});
      }
    }
  }
  // The merge of two sorted lists: a pair only in the last step's ends, one only
  // in this step's begins.
  events_.clear();
  const auto event = [step](SensorEventKind kind, const Pair& p) {
    return SensorEvent{
        kind, step, {p.sensor, p.sensor_generation}, {p.visitor, p.visitor_generation}};
  };
  std::size_t i = 0;
  std::size_t j = 0;
  while (i < current_.size() || j < next_.size()) {
    if (j == next_.size() || (i < current_.size() && current_[i] < next_[j])) {
      events_.push_back(event(SensorEventKind::End, current_[i++]));
    } else if (i == current_.size() || next_[j] < current_[i]) {
      events_.push_back(event(SensorEventKind::Begin, next_[j++]));
    } else {
      ++i;
      ++j;
    }
  }
  current_.swap(next_);
  return events_.size();
}

}  // namespace phys
