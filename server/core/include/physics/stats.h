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
  std::uint64_t contacts = 0;           // overlapping pairs resolved
  std::uint64_t swept_hits = 0;         // time-of-impact stops against static bodies
  std::uint64_t friction_holds = 0;     // contacts held in place by static friction
  std::uint64_t broadphase_reuses = 0;  // sub-steps that reused the last candidate pairs
  std::uint64_t restitution_passes = 0;
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

// Seconds spent in each phase of the last step() (all zero unless profiling is on).
struct StepProfile {
  double integrate = 0.0;    // friction, acceleration, gravity, moves
  double broadphase = 0.0;   // grid build and candidate pairs
  double narrowphase = 0.0;  // exact overlap and swept tests (and contact events' touch tests)
  double resolve = 0.0;      // penetration resolution and restitution
  double sleep = 0.0;        // sleep and wake bookkeeping
  double total = 0.0;
};

}  // namespace phys
