// What the step notes for contact events (physics/contact_events.h), when they are
// on: the swept hits of the moves, and the pairs touching after the position
// passes. Neither changes a body; with events off neither runs.
// Reads: the bodies and the candidates. Writes: the world's ContactTracker.
#include <algorithm>
#include <cmath>

#include "step_phases.h"
#include "step_shared.h"

namespace phys {

namespace {

// Where two shapes touch: the normal from a toward b, how far apart their surfaces
// are along it (negative: overlapping), and the midpoint between the surfaces.
struct PairGeometry {
  Vec2 normal;
  double gap;
  Vec2 point;
};

PairGeometry circles(const Body& a, const Body& b) {
  const Vec2 d = b.position - a.position;
  const double distance = length(d);
  // Coincident centres have no direction: "up", as collide_circles says.
  const Vec2 n = distance > 0.0 ? d * (1.0 / distance) : Vec2{0.0, 1.0};
  const double gap = distance - a.radius - b.radius;
  return {n, gap, a.position + n * (a.radius + 0.5 * gap)};
}

PairGeometry circle_box(const Body& circle, const Body& box) {
  const Aabb bounds = box.bounds();
  const Vec2 c = circle.position;
  const Vec2 closest{std::clamp(c.x, bounds.min.x, bounds.max.x),
                     std::clamp(c.y, bounds.min.y, bounds.max.y)};
  const Vec2 d = closest - c;
  const double distance = length(d);
  if (distance > 0.0) {
    const Vec2 n = d * (1.0 / distance);
    const double gap = distance - circle.radius;
    return {n, gap, c + n * (circle.radius + 0.5 * gap)};
  }
  // The centre inside the box: through its nearest face, as the narrowphase does.
  const Contact inside = collide_circle_box(c, circle.radius, bounds);
  return {inside.normal, -inside.penetration, c};
}

PairGeometry boxes(const Body& a, const Body& b) {
  const Vec2 d = b.position - a.position;
  const double apart_x = std::fabs(d.x) - (a.half.x + b.half.x);
  const double apart_y = std::fabs(d.y) - (a.half.y + b.half.y);
  const Aabb ba = a.bounds();
  const Aabb bb = b.bounds();
  // The middle of the two boxes' common part (of the gap between them, on an axis
  // they are apart on).
  const Vec2 point{0.5 * (std::max(ba.min.x, bb.min.x) + std::min(ba.max.x, bb.max.x)),
                   0.5 * (std::max(ba.min.y, bb.min.y) + std::min(ba.max.y, bb.max.y))};
  // The axis they are furthest apart on (least overlapping) is the normal's.
  if (apart_x > apart_y) return {{d.x >= 0.0 ? 1.0 : -1.0, 0.0}, apart_x, point};
  return {{0.0, d.y >= 0.0 ? 1.0 : -1.0}, apart_y, point};
}

PairGeometry measure(const Body& a, const Body& b) {
  if (a.shape == Shape::Circle && b.shape == Shape::Circle) return circles(a, b);
  if (a.shape == Shape::Circle) return circle_box(a, b);
  if (b.shape == Shape::Circle) {
    PairGeometry g = circle_box(b, a);
    g.normal = Vec2{} - g.normal;  // +0, not -0, in a zero component
    return g;
  }
  return boxes(a, b);
}

}  // namespace

void note_touching_pairs(const StepContext& ctx, WorldImpl& w) {
  ContactTracker& tracker = w.contact_tracker;
  tracker.mark_stepped(w.lists.active, w.bodies.size());
  const double margin = near_miss_margin(ctx.settings);
  for (const Candidate& cand : w.candidates.list) {
    const Body& a = w.bodies[cand.lower];
    const Body& b = w.bodies[cand.upper];
    Aabb grown = a.bounds();
    grown.min -= Vec2{margin, margin};
    grown.max += Vec2{margin, margin};
    if (!boxes_intersect(grown, b.bounds())) continue;
    const PairGeometry g = measure(a, b);
    if (!(g.gap <= margin)) continue;
    // A fixed body (static, or asleep) has no velocity for the solver either.
    const Vec2 vb = cand.fixed ? Vec2{} : b.velocity;
    tracker.note({cand.lower, a.generation}, {cand.upper, b.generation}, g.point, g.normal,
                 -dot(vb - a.velocity, g.normal));
  }
  w.counters.contact_pair_tests += w.candidates.list.size();
}

void note_swept_hit(WorldImpl& w, const Body& mover, std::uint32_t mover_slot, int axis,
                    double level, double speed, std::uint32_t obstacle_slot) {
  Body at_impact = mover;
  component(at_impact.position, axis) = level;
  component(at_impact.velocity, axis) = speed;
  const PairGeometry g = measure(at_impact, w.bodies[obstacle_slot]);
  // The obstacle is static or asleep: still.
  w.contact_tracker.note({mover_slot, mover.generation},
                         {obstacle_slot, w.bodies[obstacle_slot].generation}, g.point, g.normal,
                         dot(at_impact.velocity, g.normal));
}

}  // namespace phys
