#pragma once
// What the world reports about its own work: how often each stage ran (so a test
// can see a stage skipped) and how long each phase of the last step took.
#include <cstdint>

namespace phys {

// Counts since the world was created. A stage that a scene does not need is never
// run, so its counter stays where it was.
struct StageCounters {
  std::uint64_t steps = 0;              // calls to step()
  std::uint64_t substeps = 0;           // sub-steps run
  std::uint64_t friction_passes = 0;    // friction stage runs
  std::uint64_t gravity_passes = 0;     // gravity term added
  std::uint64_t bodies_integrated = 0;  // dynamic, awake bodies advanced
  std::uint64_t box_box_tests = 0;      // narrowphase box-box tests
  std::uint64_t circle_circle_tests = 0;
  std::uint64_t circle_box_tests = 0;
  // Pairs the position passes after the second updated from the bodies' moves
  // (WorldSettings::relaxed_position_passes) instead of the narrowphase.
  std::uint64_t relaxed_pair_updates = 0;
  std::uint64_t contacts = 0;           // overlapping pairs resolved
  std::uint64_t swept_hits = 0;         // time-of-impact stops against static bodies
  std::uint64_t friction_holds = 0;     // contacts held in place by static friction
  std::uint64_t broadphase_reuses = 0;  // sub-steps that reused the last candidate pairs
  // Of those, the sub-steps whose processing order had changed: the kept pairs were
  // renumbered to it rather than found anew.
  std::uint64_t broadphase_renumbers = 0;
  std::uint64_t velocity_solves = 0;  // sub-steps whose velocity solver had contacts
  // Contacts with an impulse left out of warm starting: their lower body's
  // warm-start slots (kWarmSlots) were full.
  std::uint64_t warm_start_overflows = 0;
  std::uint64_t sleeping_bodies_skipped = 0;
  std::uint64_t wakes = 0;         // sleeping bodies woken by a hit
  std::uint64_t speed_clamps = 0;  // velocities clamped to max_speed
  std::uint64_t acceleration_clamps = 0;
  std::uint64_t bounds_clamps = 0;  // dynamic bodies held inside the bounds
  // Contact events (World::set_contact_events); both stay 0 while they are off.
  std::uint64_t contact_pair_tests = 0;  // candidate pairs tested for touching
  std::uint64_t contact_events = 0;      // begin and end events produced

  bool operator==(const StageCounters&) const = default;
};

// Seconds spent in each phase of the last step(), over all its sub-steps (all zero
// unless WorldSettings::profile is on). The phases are the sub-step's recipe
// (server/core/src/step.cpp); total is the whole step, the rebuild of the body
// lists included.
struct StepProfile {
  double order_and_integrate = 0.0;  // the processing order; friction, acceleration, gravity
  double candidates = 0.0;           // the broadphase: fat boxes, grid, candidate pairs
  double moves = 0.0;                // the per-axis moves, swept against static bodies
  double position_passes = 0.0;      // penetration resolution, contacts and near misses
  double contact_events = 0.0;       // touching pairs and events (only when they are on)
  double velocity_solver = 0.0;      // restitution, friction, warm start, held support
  double bounds_and_sleep = 0.0;     // the world's bounds, waking what was hit, sleep
  double total = 0.0;
};

}  // namespace phys
