// The lists of awake bodies and of static and sleeping ones are updated from the
// bodies that fell asleep or woke since they were last built (body_lists.cpp), not
// rebuilt from every body. The update must give the rebuild's lists exactly.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "physics_test_support.h"
#include "scenes/random.h"

namespace phys::testing {
namespace {

using scenes::Rain;

struct Pile {
  World world;
  BodyId floor;
  std::vector<BodyId> circles;
};

// 400 circles rained into a container 20 m wide, which fall asleep from the floor
// up over a few seconds.
void rain_pile(Pile& pile) {
  pile.floor = add_or_fail(pile.world, box_def({0.0, -0.5}, {11.0, 0.5}, Motion::Static));
  add_or_fail(pile.world, box_def({-10.5, 20.0}, {0.5, 20.0}, Motion::Static));
  add_or_fail(pile.world, box_def({10.5, 20.0}, {0.5, 20.0}, Motion::Static));
  Rain rain;
  for (int i = 0; i < 400; ++i) {
    const Vec2 at{-9.0 + (i % 18) + rain.uniform(-0.05, 0.05), 1.0 + 1.1 * (i / 18)};
    BodyDef def = circle_def(at, 0.5);
    def.velocity = {rain.uniform(-1.0, 1.0), 0.0};
    pile.circles.push_back(add_or_fail(pile.world, def));
  }
}

// Bound: a world made to rebuild its lists from every body (a static body moved
// by hand, to where it already is) whenever the other updates them, keeps the
// same state hash and the same count of sleeping bodies at every step of 15 s: while the pile falls
// asleep from the floor up, after bodies woken by hand between steps (some of them just as they
// fell asleep, before the lists saw it), and after a body dropped on the sleeping pile wakes what
// it hits.
TEST(BodyLists, UpdatingFromTheChangedBodiesGivesTheWholeRebuildsLists) {
  Pile updated;
  Pile rebuilt;
  rain_pile(updated);
  rain_pile(rebuilt);
  const Vec2 floor_at = rebuilt.world.body(rebuilt.floor)->position;
  // What the lists were last built from: how many bodies were awake, and had woken.
  std::size_t awake_at_build = 0;
  std::uint64_t wakes_at_build = 0;
  int partly_asleep_steps = 0;
  int woken_as_they_slept = 0;
  std::vector<bool> was_awake(updated.circles.size(), true);
  for (int step = 1; step <= 900; ++step) {
    if (step == 400 || step == 700) {  // wake a few sleeping circles by hand
      for (std::size_t i = 0; i < updated.circles.size(); i += 37) {
        ASSERT_TRUE(updated.world.set_velocity(updated.circles[i], {0.5, 0.0}));
        ASSERT_TRUE(rebuilt.world.set_velocity(rebuilt.circles[i], {0.5, 0.0}));
      }
    }
    if (step == 600) {  // a circle dropped on the pile
      add_or_fail(updated.world, circle_def({0.3, 30.0}, 0.5));
      add_or_fail(rebuilt.world, circle_def({0.3, 30.0}, 0.5));
    }
    // Whenever bodies fell asleep or woke since the lists were built (in the last
    // step or by hand), the rebuilt world is made to walk every body.
    const std::size_t awake = rebuilt.world.awake_body_count();
    const std::uint64_t wakes = rebuilt.world.counters().wakes;
    if (awake != awake_at_build || wakes != wakes_at_build) {
      ASSERT_TRUE(rebuilt.world.set_position(rebuilt.floor, floor_at));
    }
    awake_at_build = awake;
    wakes_at_build = wakes;
    for (std::size_t i = 0; i < updated.circles.size(); ++i) {
      was_awake[i] = updated.world.body(updated.circles[i])->awake;
    }
    updated.world.step(kDt);
    rebuilt.world.step(kDt);
    ASSERT_EQ(updated.world.state_hash(), rebuilt.world.state_hash()) << "step " << step;
    // The sleeping bodies counted as such, step by step.
    ASSERT_EQ(updated.world.counters().sleeping_bodies_skipped,
              rebuilt.world.counters().sleeping_bodies_skipped)
        << "step " << step;
    if (awake > 0 && awake < updated.circles.size()) ++partly_asleep_steps;
    if (step >= 250 && step < 300) {  // wake by hand what fell asleep in this step
      for (std::size_t i = 0; i < updated.circles.size(); ++i) {
        if (was_awake[i] && !updated.world.body(updated.circles[i])->awake) {
          ASSERT_TRUE(updated.world.set_velocity(updated.circles[i], {0.0, 0.0}));
          ASSERT_TRUE(rebuilt.world.set_velocity(rebuilt.circles[i], {0.0, 0.0}));
          ++woken_as_they_slept;
        }
      }
    }
  }
  // The run went through what the update handles: a pile partly asleep for
  // seconds, and bodies woken both by hand and by hits.
  EXPECT_GT(partly_asleep_steps, 120);
  EXPECT_GT(updated.world.counters().wakes, 20u);
  EXPECT_GT(woken_as_they_slept, 5);
}

}  // namespace
}  // namespace phys::testing
