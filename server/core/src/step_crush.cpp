// Crushes (physics/crush_events.h): a dynamic body pinned between a kinematic body
// and a static one. The position passes push each pair apart in turn, so between a
// kinematic and a static body the pair resolved last would win: when it was the
// kinematic one, the body was left inside the static body, pushed deeper every
// sub-step, and came out on its far side. Before each collide phase, in a world
// with kinematic bodies, this finds the bodies a kinematic body presses against a
// static one by more than the room left between them: for those the static body
// has the last word (the passes skip the kinematic pushes toward it), the crush is
// recorded, and the velocity solver takes away their velocity into the static body.
// Reads: the candidates, the bodies. Writes: scratch.position.pinned and
// pin_normal, WorldImpl::crushes.
#include <algorithm>
#include <cmath>

#include "step_phases.h"
#include "step_shared.h"

namespace phys {

namespace {

// How two bodies meet: the normal from a toward b, and how deep they overlap
// (below 0: how far apart); `near` is false when they are apart by more than
// `reach`, or apart on both axes (two boxes corner to corner).
struct Meeting {
  Vec2 normal{};
  double depth = 0.0;
  bool near = false;
};

Meeting meet(const Body& a, const Body& b, double reach) {
  if (a.shape == Shape::Box && b.shape == Shape::Box) {
    const Vec2 d = b.position - a.position;
    const double ox = a.half.x + b.half.x - std::fabs(d.x);
    const double oy = a.half.y + b.half.y - std::fabs(d.y);
    if ((ox < 0.0 && oy < 0.0) || std::min(ox, oy) < -reach) return {};
    // The shallower axis, as the position passes resolve a pair of boxes.
    if (ox < oy) return {{d.x >= 0.0 ? 1.0 : -1.0, 0.0}, ox, true};
    return {{0.0, d.y >= 0.0 ? 1.0 : -1.0}, oy, true};
  }
  Contact contact;
  if (a.shape == Shape::Circle && b.shape == Shape::Circle) {
    contact = collide_circles(a.position, a.radius + reach, b.position, b.radius);
  } else if (a.shape == Shape::Circle) {
    contact = collide_circle_box(a.position, a.radius + reach, b.bounds());
  } else {
    contact = collide_circle_box(b.position, b.radius + reach, a.bounds());
    contact.normal = -contact.normal;
  }
  if (!contact.colliding) return {};
  return {contact.normal, contact.penetration - reach, true};
}

}  // namespace

void find_pinned_bodies(const StepContext& ctx, WorldImpl& w) {
  StepScratch::Position& x = w.scratch.position;
  const std::size_t active = w.lists.active.size();
  for (const std::uint32_t p : x.pinned) x.pin_normal[p] = {};
  x.pinned.clear();
  x.pin_normal.resize(active);
  const double slop = ctx.settings.slop;
  const double margin = near_miss_margin(ctx.settings);
  const Candidate* const cands = w.candidates.list.data();
  for (std::uint32_t p = 0; p < active; ++p) {
    const std::uint32_t begin = w.candidates.first[p];
    const std::uint32_t end = w.candidates.first[p + 1];
    for (std::uint32_t k = begin; k < end && x.pin_normal[p] == Vec2{}; ++k) {
      const Body& kinematic = w.bodies[cands[k].upper];
      if (!cands[k].fixed || kinematic.motion != Motion::Kinematic) continue;
      const Body& body = w.bodies[cands[k].lower];
      const Meeting pressed = meet(body, kinematic, margin);
      if (!pressed.near) continue;
      // A static body on the far side, the two closer than the body is wide: the
      // kinematic body moved into it, or it moved into the static one with the
      // velocity the kinematic one gave it.
      for (std::uint32_t s = begin; s < end; ++s) {
        const Body& fixed = w.bodies[cands[s].upper];
        if (!cands[s].fixed || fixed.motion != Motion::Static) continue;
        const Meeting wall = meet(body, fixed, std::max(pressed.depth, 0.0) + margin);
        if (!wall.near || dot(wall.normal, pressed.normal) >= 0.0) continue;
        if (pressed.depth + wall.depth <= slop) continue;  // room between them
        // Kept awake while pinned: a crush is reported every step it lasts, even
        // under a kinematic body at rest (which wakes nothing).
        w.bodies[cands[k].lower].still_time = 0.0;
        x.pin_normal[p] = wall.normal;
        x.pinned.push_back(p);
        w.record_crush(cands[k].upper, cands[k].lower, cands[s].upper);
        break;
      }
    }
  }
}

}  // namespace phys
