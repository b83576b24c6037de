// The position passes: overlapping pairs pushed apart by penetration plus slop
// (boxes one axis at a time, circles along their normal), with shock propagation,
// static friction, and the contacts and near misses the velocity solver needs.
// Reads: the candidates, the bodies, scratch.motion.step_start (static friction).
// Writes: the bodies' positions and corrections; scratch.marks, supported,
// position and to_wake.
// This file: the box pairs, one axis at a time, and the two phases; the pair loop
// and the contact rules are in step_position_pass.h, the circles in
// step_position_circles.cpp.
#include <algorithm>
#include <cmath>

#include "step_phases.h"
#include "step_position_pass.h"

namespace phys {
namespace {

// Per-axis resolution of box pairs: the recipe's penetration on the axis, pushed
// apart by penetration plus slop, up if above, down if below. The axis is a
// template argument: picking a component by a run-time axis cost a branch per
// use, and the registers those branches tied up spilled the pair loop's state.
template <int axis>
inline void PositionPass::collide_boxes_on() {
  constexpr int other = 1 - axis;
  const Vec2 unit = axis == 0 ? Vec2{1.0, 0.0} : Vec2{0.0, 1.0};
  std::uint64_t tests = 0;  // counted here, added once: the loop keeps it in a register
  resolve_passes([&](const Candidate& cand, Body& a, Body& b) __attribute__((always_inline)) {
    if (a.shape != Shape::Box || b.shape != Shape::Box) return false;
    ++tests;
    const Aabb ba = a.bounds();
    const Aabb bb = b.bounds();
    // Touching on the other axis only (side by side): that axis resolves it.
    const double across = std::min(component(ba.max, other), component(bb.max, other)) -
                          std::max(component(ba.min, other), component(bb.min, other));
    if (across <= 0.5 * s_.slop) return false;
    const double ca = component(a.position, axis);
    const double cb = component(b.position, axis);
    const Vec2 n = (cb >= ca) ? unit : -unit;  // from a toward b
    const double gap = std::min(component(ba.max, axis), component(bb.max, axis)) -
                       std::max(component(ba.min, axis), component(bb.min, axis));
    if (gap < 0.0) {  // apart on this axis: a near miss, or nothing
      // Two dynamic boxes side by side (across gravity) fall together and carry
      // nothing of each other: their near miss would only add work to a stack's
      // velocity pass (a third of it in the 5,050-box pyramid).
      const bool side_by_side = !cand.fixed && std::fabs(dot(n, c_.up)) < 1.0 - kAlongGravity;
      if (-gap <= near_miss_margin() && !side_by_side) record_near_miss(cand, n, -gap);
      return false;
    }
    const double depth = axis_penetration(ca, component(a.half, axis), cb, component(b.half, axis));
    // Resolve on this axis only if it is the shallower one. Otherwise a box that
    // sank a little into a floor tile would be thrown sideways by the tile's
    // width (catching on seams), or lifted by a neighbour's height.
    if (depth > across) return false;
    return separate(cand, a, b, n, depth);
  });
  w_.counters.box_box_tests += tests;
}

}  // namespace

// The Y phase: boxes on Y (circles wait for the X phase).
void collide_on_y(const StepContext& ctx, WorldImpl& w, const Order& order,
                  const FreeMotion& motion) {
  if (w.kinematic_count() != 0) find_pinned_bodies(ctx, w);
  PositionPass(ctx, w, order, motion).collide_boxes_on<1>();
}

// The X phase: boxes on X, then every pair with a circle.
void collide_on_x(const StepContext& ctx, WorldImpl& w, const Order& order,
                  const FreeMotion& motion) {
  if (w.kinematic_count() != 0) find_pinned_bodies(ctx, w);
  PositionPass pass(ctx, w, order, motion);
  if (motion.any_box) pass.collide_boxes_on<0>();
  if (!motion.any_circle && !(motion.any_box && w.lists.fixed_circles > 0)) return;
  collide_circle_pairs(ctx, w, order, motion);
}

}  // namespace phys
