// Sleep from the bottom up (docs/PHYSICS.md, "Sleep"): a still
// body whose every support is asleep or static sleeps although something above it
// in its island still moves; so does a still group held up by friction with no
// contact below (held groups); and a sleeping body an awake one presses into from
// below wakes, however slowly it is pressed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "physics_test_support.h"

namespace phys::testing {
namespace {

// A column of `count` unit boxes standing on a static floor, bottom first.
std::vector<BodyId> add_box_column(World& world, int count, double mass_of_top) {
  add_or_fail(world, box_def({0.0, -0.5}, {20.0, 0.5}, Motion::Static));
  std::vector<BodyId> ids;
  for (int i = 0; i < count; ++i) {
    BodyDef def = box_def({0.0, 0.5 + i}, {0.5, 0.5});
    if (i == count - 1) def.mass = mass_of_top;
    ids.push_back(add_or_fail(world, def));
  }
  return ids;
}

// Drives a body sideways at 0.3 m/s, turning every second (set each step, as a
// client's input would), leaving its vertical velocity to gravity and contacts.
void drive_back_and_forth(World& world, BodyId id, int step) {
  const bool forward = (step / 60) % 2 == 0;
  const double fall = world.body(id)->velocity.y;
  ASSERT_TRUE(world.set_velocity(id, {forward ? 0.3 : -0.3, fall}));
}

// A column of 5 boxes with a 6th sliding back and forth on top of it at 0.3 m/s,
// turning every second (set each step, as a client's input would; frictionless
// contacts, so the column feels only its weight). The slider never stops, so the
// island of six is never still as a whole; before this rule all six stayed awake.
// Bound: from 2 s on, the five boxes of the column are asleep at every step and the
// slider awake; the slider stays on the column (within 0.01 m of resting height).
TEST(PartialSleep, ColumnSleepsUnderABodyThatKeepsMoving) {
  World world;
  const std::vector<BodyId> column = add_box_column(world, 5, 1.0);
  const BodyId slider = add_or_fail(world, box_def({0.0, 5.5}, {0.5, 0.5}));
  int column_awake_steps = 0;
  int slider_asleep_steps = 0;
  double worst_height_error = 0.0;
  for (int step = 1; step <= 600; ++step) {
    drive_back_and_forth(world, slider, step);
    world.step(kDt);
    if (step < 120) continue;
    for (const BodyId id : column) column_awake_steps += world.body(id)->awake ? 1 : 0;
    slider_asleep_steps += world.body(slider)->awake ? 0 : 1;
    worst_height_error =
        std::max(worst_height_error, std::fabs(world.body(slider)->position.y - 5.5));
  }
  EXPECT_EQ(column_awake_steps, 0) << "box-steps of the column awake from 2 s on";
  EXPECT_EQ(slider_asleep_steps, 0);
  EXPECT_LT(worst_height_error, 0.01) << "m";
}

// The same pile rule must not put a body to sleep on one that is still moving:
// a column on a box that slides on the floor stays awake all the way up.
// Bound: while the bottom box is driven, no box of the column sleeps.
TEST(PartialSleep, NothingSleepsOnAMovingSupport) {
  World world;
  const std::vector<BodyId> column = add_box_column(world, 4, 1.0);
  int asleep_steps = 0;
  for (int step = 1; step <= 300; ++step) {
    // The bottom box is pushed back and forth; the boxes on it ride along on their
    // contacts (no friction: they slide off it slowly, still moving).
    const bool forward = (step / 60) % 2 == 0;
    ASSERT_TRUE(world.set_velocity(column[0], {forward ? 0.2 : -0.2, 0.0}));
    world.step(kDt);
    for (std::size_t i = 1; i < column.size(); ++i) {
      asleep_steps += world.body(column[i])->awake ? 0 : 1;
    }
  }
  // The boxes above do not move with it (frictionless), so they are still; what
  // must hold is that none of them sleeps while the box under the column moves.
  EXPECT_EQ(asleep_steps, 0) << "box-steps asleep on a moving support";
}

// A light box asleep on a heavy one, which is then pushed up by an acceleration
// only a little above gravity: it closes on the sleeping box at 0.02 m/s a step,
// below the 0.05 m/s that counts as a hit, so before the rule the sleeping box
// stayed a ceiling and the pair never rose. Bound: the light box wakes at once,
// the pair has risen by more than 0.5 m after 3 s (free rise of the pair:
// (11 - 9.81 * 1.1) / 1.1 m/s^2, 0.8 m), and the boxes never overlap by more
// than the slop's order (1e-3 m).
TEST(PartialSleep, ABoxPressedFromBelowWakes) {
  World world;
  const std::vector<BodyId> pair = add_box_column(world, 2, 0.1);
  for (int step = 0; step < 120; ++step) world.step(kDt);
  ASSERT_FALSE(world.body(pair[0])->awake) << "the pair should be asleep before the push";
  ASSERT_FALSE(world.body(pair[1])->awake);
  ASSERT_TRUE(world.set_acceleration(pair[0], {0.0, 11.0}));  // on top of gravity's -9.81
  const double start = world.body(pair[1])->position.y;
  double worst_overlap = 0.0;
  bool woke_at_once = false;
  for (int step = 1; step <= 180; ++step) {
    world.step(kDt);
    if (step == 2) woke_at_once = world.body(pair[1])->awake;
    const double gap = world.body(pair[1])->position.y - world.body(pair[0])->position.y - 1.0;
    worst_overlap = std::max(worst_overlap, -gap);
  }
  const double risen = world.body(pair[1])->position.y - start;
  std::printf("pressed from below: risen %.3f m, worst overlap %.3g m\n", risen, worst_overlap);
  EXPECT_TRUE(woke_at_once);
  EXPECT_GT(risen, 0.5) << "m";
  EXPECT_LT(worst_overlap, 1e-3) << "m";
}

// Held groups (docs/PHYSICS.md, "Sleep"): a box with no contact below it, pressed
// against a static wall by its own acceleration (1.5 g) and held up by friction
// (mu 1 on both), carries a light box with a slider on top that never stops (as in
// ColumnSleepsUnderABodyThatKeepsMoving). The island is never still as a whole, and
// the bottom-up rule needs a contact below, so before held groups the pressed box
// and the box on it stayed awake for ever (creeping down the wall at 1.4 cm/s).
// Bound: from 2 s on, the pressed box and the box on it are asleep at every step
// and the slider awake; the pressed box moves less than 1e-3 m in that time.
TEST(PartialSleep, ABoxHeldUpByFrictionSleepsWithWhatItCarries) {
  World world;
  BodyDef wall = box_def({-1.0, 5.0}, {0.5, 5.0}, Motion::Static);  // right face at x = -0.5
  wall.contact_friction = 1.0;
  add_or_fail(world, wall);
  BodyDef pressed_def = box_def({0.0, 3.0}, {0.5, 0.5});
  pressed_def.contact_friction = 1.0;
  pressed_def.acceleration = {-1.5 * 9.81, 0.0};
  const BodyId pressed = add_or_fail(world, pressed_def);
  BodyDef carried_def = box_def({0.0, 4.0}, {0.5, 0.5});
  carried_def.mass = 0.1;
  carried_def.contact_friction = 1.0;
  const BodyId carried = add_or_fail(world, carried_def);
  BodyDef slider_def = box_def({0.0, 5.0}, {0.5, 0.5});
  slider_def.mass = 0.1;  // frictionless on the carried box: it slides, never drags
  const BodyId slider = add_or_fail(world, slider_def);
  int held_awake_steps = 0;
  int slider_asleep_steps = 0;
  double start_height = 0.0;
  for (int step = 1; step <= 600; ++step) {
    drive_back_and_forth(world, slider, step);
    world.step(kDt);
    if (step == 120) start_height = world.body(pressed)->position.y;
    if (step < 120) continue;
    held_awake_steps += world.body(pressed)->awake ? 1 : 0;
    held_awake_steps += world.body(carried)->awake ? 1 : 0;
    slider_asleep_steps += world.body(slider)->awake ? 0 : 1;
  }
  const double moved = std::fabs(world.body(pressed)->position.y - start_height);
  std::printf("held up by friction: pressed box moved %.3g m from 2 s to 10 s\n", moved);
  EXPECT_EQ(held_awake_steps, 0) << "body-steps awake from 2 s on";
  EXPECT_EQ(slider_asleep_steps, 0);
  EXPECT_LT(moved, 1e-3) << "m";
}

}  // namespace
}  // namespace phys::testing
