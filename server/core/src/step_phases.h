#pragma once
// The phases of one sub-step, in the classic recipe's order (docs/PHYSICS.md):
//   friction; acceleration and gravity; move on Y, collide on Y; move on X,
//   collide on X; restitution (the velocity solver).
// plus what the recipe leaves out and a server needs: a broadphase, swept motion
// against static bodies (nothing tunnels), shock propagation for stacks, and sleep.
// step.cpp runs them (run_sub_step); each is defined in its own file, with its
// helpers file-local there. What a phase hands on to a later one is in its
// arguments and results below; the arrays behind them are the world's scratch
// (step_scratch.h).
#include <cstdint>
#include <span>

#include "step_context.h"
#include "world_impl.h"

namespace phys {

// step_kinematic.cpp: the kinematic bodies move by their velocity (with lists.kinematic
// not empty), first in the sub-step.
void move_kinematic_bodies(WorldImpl& w, double h);

// step_order.cpp: the processing order of the awake bodies, lowest first.
struct Order {
  bool changed;  // the order is not last sub-step's (the candidates' positions are stale)
  // Only moves within the kept order changed it, and scratch.order.from says where
  // each body was: the candidate pairs may be kept, renumbered.
  bool from_known;
  bool scattered;  // far from slot order: the walks over the bodies prefetch them
};
Order order_by_height(const StepContext& ctx, WorldImpl& w);

// step_integrate.cpp: friction, acceleration and gravity as each body's free
// motion (in scratch.motion), and the candidate pairs it can reach.
struct FreeMotion {
  bool all_inside;  // every body inside its fat box: the pairs still hold
  // The new fat boxes (scratch.motion.next_fat_boxes) are made from this position
  // on: 0, all of them; the body count, none.
  std::size_t fat_from;
  bool any_box;               // an awake body is a box
  bool any_circle;            // an awake body is a circle
  bool any_contact_friction;  // an awake body has contact friction
};
FreeMotion integrate(const StepContext& ctx, WorldImpl& w, const Order& order);
void find_candidates(const StepContext& ctx, WorldImpl& w, const Order& order,
                     const FreeMotion& motion);

// step_moves.cpp: the free motion applied along one axis, or both (Y then X, in one
// walk, when no awake box needs the Y collision in between), swept against static
// and sleeping bodies.
void move_on_axis(const StepContext& ctx, WorldImpl& w, int axis);
void move_both_axes(const StepContext& ctx, WorldImpl& w);

// step_position.cpp: the position passes (penetration resolution), boxes on Y, then
// boxes on X and every pair with a circle.
void collide_on_y(const StepContext& ctx, WorldImpl& w, const Order& order,
                  const FreeMotion& motion);
void collide_on_x(const StepContext& ctx, WorldImpl& w, const Order& order,
                  const FreeMotion& motion);

// step_crush.cpp: in a world with kinematic bodies, before each collide phase, the
// bodies a kinematic body pins against a static one (physics/crush_events.h).
void find_pinned_bodies(const StepContext& ctx, WorldImpl& w);

// step_velocity.cpp: the velocity solver (restitution, contact friction, shock
// propagation, warm start, held support, waking what is hit). Returns this
// sub-step's contact records.
std::span<const ContactRecord> solve_velocities(const StepContext& ctx, WorldImpl& w,
                                                const Order& order, const FreeMotion& motion);

// step_contact_memory.cpp: what the contacts leave for the next sub-step, after
// the velocity solver (with contacts only): their impulses for the warm start, and
// (with shock propagation and contact friction) the bodies' load factors.
void remember_impulses(WorldImpl& w, std::span<const ContactRecord> contacts);
void update_loads(const StepContext& ctx, WorldImpl& w, const Order& order,
                  std::span<const ContactRecord> contacts);

// step_contact_events.cpp: what contact events need noted (only when they are on).
void note_touching_pairs(const StepContext& ctx, WorldImpl& w);
void note_swept_hit(WorldImpl& w, const Body& mover, std::uint32_t mover_slot, int axis,
                    double level, double speed, std::uint32_t obstacle_slot);

// step_sleep.cpp: the world's bounds, and sleep.
void hold_in_bounds(const StepContext& ctx, WorldImpl& w);
void update_sleep(const StepContext& ctx, WorldImpl& w, const Order& order,
                  std::span<const ContactRecord> contacts);

}  // namespace phys
