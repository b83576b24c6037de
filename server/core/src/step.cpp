// The recipe of a sub-step: its phases in order and what flows between them
// (step_phases.h), each timed into the step's profile when profiling is on; and
// WorldImpl::step, the sub-steps of one step.
#include <chrono>
#include <span>

#include "phase_timer.h"
#include "step_phases.h"
#include "step_shared.h"

namespace phys {

namespace {

void run_sub_step(WorldImpl& w, double h) {
  if (w.kinematic_count() != 0) move_kinematic_bodies(w, h);
  const BodyLists& lists = w.current_lists();
  w.counters.sleeping_bodies_skipped += lists.fixed_sleeping;
  if (lists.active.empty()) return;
  const StepContext ctx(w.settings, h);
  const bool timed = w.settings.profile;
  StepProfile& profile = w.profile;

  // Friction, acceleration and gravity: each awake body's free motion, lowest first.
  Order order{};
  FreeMotion motion{};
  {
    PhaseTimer t(timed, profile.order_and_integrate);
    order = order_by_height(ctx, w);
    motion = integrate(ctx, w, order);
  }
  {
    PhaseTimer t(timed, profile.candidates);
    find_candidates(ctx, w, order, motion);
  }
  // The contacts of this sub-step, marked by the moves and the position passes.
  StepScratch::Marks& marks = w.scratch.marks;
  const std::size_t candidates = w.candidates.list.size();
  marks.contact_of.assign(candidates, kNone);
  marks.normal.resize(candidates);
  marks.near_miss.resize(candidates);
  marks.gap.resize(candidates);
  // Move on Y, collide on Y; move on X, collide on X. With no awake box there is no
  // collision on Y: both moves are one walk.
  if (motion.any_box) {
    {
      PhaseTimer t(timed, profile.moves);
      move_on_axis(ctx, w, 1);
    }
    {
      PhaseTimer t(timed, profile.position_passes);
      collide_on_y(ctx, w, order, motion);
    }
    PhaseTimer t(timed, profile.moves);
    move_on_axis(ctx, w, 0);
  } else {
    PhaseTimer t(timed, profile.moves);
    move_both_axes(ctx, w);
  }
  {
    PhaseTimer t(timed, profile.position_passes);
    collide_on_x(ctx, w, order, motion);
  }
  if (w.contact_events_on) {
    PhaseTimer t(timed, profile.contact_events);
    note_touching_pairs(ctx, w);
  }
  // Restitution: the velocity solver, over the contacts marked above.
  std::span<const ContactRecord> contacts;
  {
    PhaseTimer t(timed, profile.velocity_solver);
    contacts = solve_velocities(ctx, w, order, motion);
    if (!contacts.empty()) {
      if (w.settings.warm_starting) remember_impulses(w, contacts);
      if (ctx.shock && motion.any_contact_friction) update_loads(ctx, w, order, contacts);
    }
  }
  PhaseTimer t(timed, profile.bounds_and_sleep);
  hold_in_bounds(ctx, w);
  update_sleep(ctx, w, order, contacts);
}

}  // namespace

void WorldImpl::step(double dt) {
  // The world reads a clock only to fill the profile, when asked to.
  std::chrono::steady_clock::time_point start{};
  if (settings.profile) start = std::chrono::steady_clock::now();
  profile = {};
  const double h = dt / settings.substeps;
  if (contact_events_on) contact_tracker.begin_step();
  for (int i = 0; i < settings.substeps; ++i) {
    run_sub_step(*this, h);
    ++counters.substeps;
  }
  ++steps;
  ++counters.steps;
  if (contact_events_on) {
    PhaseTimer t(settings.profile, profile.contact_events);
    counters.contact_events += contact_tracker.finish(steps, bodies);
  }
  // Sensor events, after the whole step: in a world without sensors, nothing (once
  // the last overlaps of removed sensors have ended).
  if (!sensors.empty() || !sensor_tracker.idle()) sensor_tracker.update(steps, *this);
  if (settings.profile) {
    profile.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
}

}  // namespace phys
