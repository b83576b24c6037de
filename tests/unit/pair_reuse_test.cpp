// Candidate pairs kept through a change of the processing order: while every
// awake body stays inside the fat box its pairs were found with, the pairs are
// kept and renumbered to the new order (step_integrate.cpp) instead of found anew.
// The kept list must be the very list the broadphase would find from the same fat
// boxes in the new order, and must cover every pair that touches.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "physics/formulas.h"
#include "physics/world.h"
#include "scenes/random.h"
#include "scenes/scenes.h"
#include "step_shared.h"
#include "world_internals.h"

namespace phys::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

bool same_candidate(const Candidate& a, const Candidate& b) {
  return a.lower == b.lower && a.upper == b.upper && a.lower_pos == b.lower_pos &&
         a.fixed == b.fixed && (a.fixed || a.upper_pos == b.upper_pos);
}

// The list collect_candidates makes from the kept fat boxes, by brute force: per
// awake body in processing order, the static and sleeping bodies its box meets (in
// their list's order), then the later awake bodies whose boxes meet it.
std::vector<Candidate> pairs_of_the_fat_boxes(const WorldImpl& w) {
  const auto& active = w.lists.active;
  const auto& fat = w.candidates.fat_boxes;
  std::vector<Candidate> pairs;
  for (std::uint32_t p = 0; p < active.size(); ++p) {
    for (std::uint32_t f = 0; f < w.lists.fixed.size(); ++f) {
      if (boxes_intersect(fat[p], w.lists.fixed_boxes[f]) &&
          w.pair_collides_or_unfiltered(active[p], w.lists.fixed[f])) {
        pairs.push_back({active[p], w.lists.fixed[f], p, kNone, true});
      }
    }
    for (std::uint32_t q = p + 1; q < active.size(); ++q) {
      if (boxes_intersect(fat[p], fat[q]) && w.pair_collides_or_unfiltered(active[p], active[q])) {
        pairs.push_back({active[p], active[q], p, q, false});
      }
    }
  }
  return pairs;
}

// Checks the world's candidate pairs after a step; returns false at the first fault.
::testing::AssertionResult candidates_hold(const World& world) {
  const WorldImpl& w = WorldInternals::of(world);
  if (!w.candidates.valid) return ::testing::AssertionSuccess();
  const auto& active = w.lists.active;
  const auto& list = w.candidates.list;
  if (w.candidates.fat_boxes.size() != active.size() ||
      w.candidates.first.size() != active.size() + 1) {
    return ::testing::AssertionFailure() << "the fat boxes or offsets are not one per position";
  }
  const std::vector<Candidate> expected = pairs_of_the_fat_boxes(w);
  if (list.size() != expected.size()) {
    return ::testing::AssertionFailure()
           << list.size() << " candidates where the fat boxes give " << expected.size();
  }
  for (std::size_t c = 0; c < list.size(); ++c) {
    if (!same_candidate(list[c], expected[c])) {
      return ::testing::AssertionFailure()
             << "candidate " << c << " is (" << list[c].lower << ", " << list[c].upper
             << ") at positions (" << list[c].lower_pos << ", " << list[c].upper_pos
             << "); the fat boxes give (" << expected[c].lower << ", " << expected[c].upper
             << ") at (" << expected[c].lower_pos << ", " << expected[c].upper_pos << ")";
    }
  }
  for (std::uint32_t p = 0; p < active.size(); ++p) {
    for (std::uint32_t c = w.candidates.first[p]; c < w.candidates.first[p + 1]; ++c) {
      if (list[c].lower_pos != p || active[p] != list[c].lower) {
        return ::testing::AssertionFailure() << "candidate " << c << " is not in its group";
      }
    }
  }
  // Every pair of awake bodies whose boxes meet now was a candidate of the sub-step
  // that brought them there.
  const auto key = [](std::uint64_t p, std::uint64_t q) { return p << 32 | q; };
  std::vector<std::uint64_t> paired;
  for (const Candidate& c : list) {
    if (!c.fixed) paired.push_back(key(c.lower_pos, c.upper_pos));
  }
  std::sort(paired.begin(), paired.end());
  for (std::uint32_t p = 0; p < active.size(); ++p) {
    for (std::uint32_t q = p + 1; q < active.size(); ++q) {
      if (boxes_intersect(w.bodies[active[p]].bounds(), w.bodies[active[q]].bounds()) &&
          w.pair_collides_or_unfiltered(active[p], active[q]) &&
          !std::binary_search(paired.begin(), paired.end(), key(p, q))) {
        return ::testing::AssertionFailure()
               << "bodies " << active[p] << " and " << active[q] << " meet but were no candidates";
      }
    }
  }
  return ::testing::AssertionSuccess();
}

// Circles and boxes of mixed sizes dropped into a box with static pegs (more than
// the handful tested one by one, so the static grid answers), some thrown.
void add_random_scene(World& world, std::uint64_t seed) {
  scenes::SplitMix64 random(seed);
  const auto add = [&world](const BodyDef& def) { ASSERT_TRUE(world.add_body(def).is_valid()); };
  BodyDef floor;
  floor.shape = Shape::Box;
  floor.motion = Motion::Static;
  floor.position = {0.0, -1.0};
  floor.half_extents = {20.0, 1.0};
  add(floor);
  for (const double x : {-21.0, 21.0}) {
    BodyDef wall = floor;
    wall.position = {x, 20.0};
    wall.half_extents = {1.0, 21.0};
    add(wall);
  }
  for (int i = 0; i < 12; ++i) {
    BodyDef peg;
    peg.shape = Shape::Circle;
    peg.motion = Motion::Static;
    peg.radius = 0.4;
    peg.position = {-16.5 + 3.0 * i, 6.0 + (i % 2)};
    add(peg);
  }
  for (int i = 0; i < 240; ++i) {  // a lattice 1.5 m apart: no body overlaps another
    BodyDef body;
    body.position = {-17.25 + 1.5 * (i % 24) + random.uniform(-0.1, 0.1), 9.0 + 1.5 * (i / 24)};
    body.velocity = {random.uniform(-3.0, 3.0), random.uniform(-1.0, 1.0)};
    if (i % 3 == 0) {
      body.shape = Shape::Box;
      body.half_extents = {random.uniform(0.2, 0.6), random.uniform(0.2, 0.6)};
    } else {
      body.shape = Shape::Circle;
      body.radius = random.uniform(0.2, 0.6);
    }
    add(body);
  }
}

void expect_pairs_hold_at_every_step(bool sleeping) {
  WorldSettings settings;
  settings.sleeping = sleeping;
  World world(settings);
  add_random_scene(world, 7);
  for (int step = 0; step < 1800; ++step) {
    world.step(kDt);
    ASSERT_TRUE(candidates_hold(world)) << "after step " << step + 1;
  }
  // The scene went through all three ways of getting pairs, so each was checked.
  const StageCounters& counted = world.counters();

  EXPECT_GT(counted.broadphase_renumbers, 20u) << "kept through a new order";
  EXPECT_GT(counted.broadphase_reuses - counted.broadphase_renumbers, 20u) << "kept as they were";
  EXPECT_GT(counted.substeps - counted.broadphase_reuses, 20u) << "found anew";
}

TEST(PairReuse, KeptPairsAreTheFatBoxesPairsAtEveryStepSleepingOff) {
  expect_pairs_hold_at_every_step(false);
}

TEST(PairReuse, KeptPairsAreTheFatBoxesPairsAtEveryStepSleepingOn) {
  expect_pairs_hold_at_every_step(true);
}

// A settled pile, every body awake: the bodies barely move, but their heights
// jitter past one another, so the processing order changes from step to step.
// The pairs are kept through it.
TEST(PairReuse, SettledPileKeepsItsPairsThroughANewOrder) {
  WorldSettings settings;
  settings.sleeping = false;
  World world(settings);
  scenes::add_to_world(world, scenes::rain_scene(1000, 0, 0, 0));
  for (int step = 0; step < 1080; ++step) world.step(kDt);
  const StageCounters before = world.counters();
  constexpr int kSteps = 240;
  for (int step = 0; step < kSteps; ++step) {
    const std::uint64_t renumbered = world.counters().broadphase_renumbers;
    world.step(kDt);
    // Every step that renumbered is checked, and every 8th (the check is quadratic in
    // the bodies: a sanitizer build would spend seconds on each of the others).
    if (world.counters().broadphase_renumbers != renumbered || step % 8 == 0) {
      ASSERT_TRUE(candidates_hold(world)) << "after step " << step + 1;
    }
  }
  const StageCounters& after = world.counters();
  const std::uint64_t substeps = after.substeps - before.substeps;
  const std::uint64_t reuses = after.broadphase_reuses - before.broadphase_reuses;
  const std::uint64_t renumbers = after.broadphase_renumbers - before.broadphase_renumbers;

  EXPECT_GT(renumbers, substeps / 6) << "the order changed in few steps: the test shows nothing";
  EXPECT_GE(reuses, substeps * 9 / 10) << "the settled pile found its pairs anew too often";
}

}  // namespace
}  // namespace phys::testing
