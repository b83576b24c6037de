// The kinematic bodies' motion over a sub-step, before anything else moves: each
// goes velocity * h, its box with it. To every other phase a kinematic body is a
// static one that has just been moved: the dynamic bodies' sweeps, position passes
// and contacts meet it where it now is, and the contacts read its velocity
// (step_velocity.cpp, step_position.cpp), which is how it pushes and carries them.
// Reads and writes: the kinematic bodies, the fixed bodies' boxes and grid; wakes
// what sleeps in a moving body's way.
#include "step_phases.h"
#include "step_shared.h"

namespace phys {

void move_kinematic_bodies(WorldImpl& w, double h) {
  w.current_lists();
  BodyLists& lists = w.lists;
  const Vec2 margin{2.0 * w.settings.slop, 2.0 * w.settings.slop};
  bool moved = false;
  bool woke = false;
  for (const std::uint32_t f : lists.kinematic) {
    const std::uint32_t slot = lists.fixed[f];
    Body& b = w.bodies[slot];
    if (b.velocity.x == 0.0 && b.velocity.y == 0.0) continue;
    const Aabb before = lists.fixed_boxes[f];
    b.position += b.velocity * h;
    const Aabb after = b.bounds();
    lists.fixed_boxes[f] = after;
    moved = true;
    // A sleeping body is a fixed one too, and fixed bodies never meet: whatever
    // sleeps where it passes wakes, and meets it from this sub-step on.
    if (lists.fixed_sleeping == 0) continue;
    const Aabb swept{
        Vec2{std::min(before.min.x, after.min.x), std::min(before.min.y, after.min.y)} - margin,
        Vec2{std::max(before.max.x, after.max.x), std::max(before.max.y, after.max.y)} + margin};
    lists.fixed_grid.find_overlaps(swept, w.scratch.kinematic_near);
    for (const std::uint32_t near : w.scratch.kinematic_near) {
      const std::uint32_t other = lists.fixed[near];
      if (w.bodies[other].is_dynamic() && w.pair_collides_or_unfiltered(slot, other)) {
        w.wake(other);
        woke = true;
      }
    }
  }
  if (!moved) return;
  // The fixed boxes moved: their grid is made again and the pairs found anew (a
  // wake has the lists rebuilt, which makes the grid from these boxes).
  if (!woke) lists.fixed_grid.build(lists.fixed_boxes);
  w.candidates.valid = false;
}

}  // namespace phys
