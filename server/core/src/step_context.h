#pragma once
// The constants of one sub-step, found once from the settings and the sub-step's
// length and read by every phase.
#include "physics/settings.h"
#include "physics/vec2.h"

namespace phys {

struct StepContext {
  StepContext(const WorldSettings& s, double sub_step)
      : settings(s),
        h(sub_step),
        gravity_on(s.gravity.x != 0.0 || s.gravity.y != 0.0),
        up(gravity_on ? -s.gravity * (1.0 / length(s.gravity)) : Vec2{0.0, 1.0}),
        rest_speed(s.rest_speed > 0.0 ? s.rest_speed : 2.0 * length(s.gravity) * sub_step),
        shock(s.shock_propagation && gravity_on),
        hold(s.hold_resting_support && gravity_on),
        speculative_margin(0.5 * length(s.gravity) * sub_step * sub_step),
        // (Never, for a limit so large that its square would overflow.)
        surely_slow(s.max_speed < 1.0e150 ? (0.5 * s.max_speed) * (0.5 * s.max_speed) : -1.0) {}

  const WorldSettings& settings;
  double h;         // the sub-step, in seconds
  bool gravity_on;  // gravity is not zero
  Vec2 up;          // against gravity (+y without it)
  double rest_speed;
  bool shock;  // shock propagation (needs gravity)
  bool hold;   // held resting support (needs gravity)
  // A support a little below a resting body is no contact for the velocity pass
  // beyond the near-miss margin, so shock propagation's marks stop there: in a deep
  // pile, whatever rests above such a gap (a column of 60 circles along a wall)
  // fell freely for steps and was pushed back up by centimetres, never asleep.
  // Gaps up to half what a body falls from rest in one sub-step (g*h*h/2, 1.4 mm
  // at 60 Hz) are speculative contacts instead (Box2D v3's speculative distance),
  // closing at most their gap in a sub-step. Zero without gravity.
  double speculative_margin;
  double surely_slow;  // squared speeds at or below this are under max_speed
};

}  // namespace phys
