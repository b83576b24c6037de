// The moves of the awake bodies along one axis at a time, swept against static and
// sleeping bodies: a move stops at the time of impact, bounces, and goes on.
// Reads: scratch.motion (the free motion), the candidates against fixed bodies.
// Writes: the bodies' positions and velocities; scratch.marks (a resting hit is a
// contact), to_wake; contact events' swept hits when they are on.
#include <cmath>

#include "step_phases.h"
#include "step_shared.h"
#include "sweep.h"

namespace phys {

namespace {

// Time-of-impact stops per body, axis and sub-step (a bounce, then maybe another).
constexpr int kMaxHitsPerMove = 4;

class MovePass : StepPhase {
 public:
  MovePass(const StepContext& ctx, WorldImpl& world) : StepPhase(ctx, world) {}
  void run(int first_axis, int last_axis);

 private:
  // The acceleration a body moves by: what drives it, less what its contacts held
  // back last sub-step (see Body::held).
  Vec2 moving_acceleration(const Body& b) const {
    return c_.gravity_on ? driving_acceleration(b) + b.held : b.acceleration;
  }
  void sweep(std::uint32_t p, Body& b, int axis, AxisPath& path);
  static Vec2 touching_normal(const Body& mover, const Body& obstacle, int axis, double toward);
};

// Moves each body on first_axis, then down to last_axis. One build, always
// prefetching: unlike integrate and the position passes, the moves gain nothing
// measurable from a twin without it (bench/compare-core.sh, thread CPU time per
// step: always prefetching, the awake pyramid-5050 ran 1.001x and rain-16000
// 1.003x / 1.021x, never 1.025x / 1.005x, all within the run-to-run noise).
inline void MovePass::run(int first_axis, int last_axis) {
  for (std::uint32_t p = 0; p < w_.lists.active.size(); ++p) {
    prefetch_ahead(p);
    Body& b = body(w_.lists.active[p]);
    // With no static or sleeping body among its candidates (they come first) the
    // sweep has nothing to hit and the free motion stands: skip building its path.
    const std::uint32_t first = w_.candidates.first[p];
    const bool near_fixed = first < w_.candidates.first[p + 1] && w_.candidates.list[first].fixed;
    for (int axis = first_axis; axis >= last_axis; --axis) {
      const double v_end = component(x_.motion.velocity[p], axis);
      const double x0 = component(b.position, axis);
      const double x_end = x0 + component(x_.motion.displacement[p], axis);
      if (!s_.continuous || !near_fixed) {
        component(b.position, axis) = x_end;
        component(b.velocity, axis) = v_end;
        continue;
      }
      const double a = component(moving_acceleration(b), axis);
      AxisPath path{
          s_.integrator, x0,   component(b.velocity, axis), a, component(b.friction, axis), c_.h,
          x_end,         v_end};
      sweep(p, b, axis, path);
      component(b.position, axis) = path.x1;
      // A bounce re-integrates the rest of the sub-step from the contact, past the
      // free motion's speed cap: the world stays finite only if it is capped again.
      double v1 = path.v1;
      if (std::fabs(v1) > s_.max_speed) {
        v1 = v1 < 0.0 ? -s_.max_speed : s_.max_speed;
        ++w_.counters.speed_clamps;
      }
      component(b.velocity, axis) = v1;
    }
  }
}

inline void MovePass::sweep(std::uint32_t p, Body& b, int axis, AxisPath& path) {
  for (int hit = 0; hit < kMaxHitsPerMove && path.x1 != path.x0; ++hit) {
    double first_t = kInfinity;
    double level = 0.0;
    double restitution = 0.0;
    std::uint32_t hit_body = kNone;
    std::uint32_t hit_candidate = kNone;
    for (std::uint32_t c = w_.candidates.first[p]; c < w_.candidates.first[p + 1]; ++c) {
      const Candidate& cand = w_.candidates.list[c];
      if (!cand.fixed) break;  // fixed candidates come first
      const Body& o = body(cand.upper);
      component(b.position, axis) = path.x0;
      const auto span = overlap_interval(b, o, axis, 0.5 * s_.slop);
      if (!span || (path.x0 >= span->lo && path.x0 <= span->hi)) continue;
      const double target = path.x0 < span->lo ? span->lo : span->hi;
      const auto t = path.reaches(target);
      if (t && *t < first_t) {
        first_t = *t;
        level = target;
        restitution = mix_restitution(b.restitution, o.restitution);
        hit_body = cand.upper;
        hit_candidate = c;
      }
    }
    if (!(first_t < kInfinity)) return;
    ++w_.counters.swept_hits;
    // Bounce at the time of impact and spend the rest of the step going back.
    const double v_hit = path.velocity(first_t);
    if (w_.contact_events_on)
      note_swept_hit(w_, b, w_.lists.active[p], axis, level, v_hit, hit_body);
    // A sleeping body struck by a swept move wakes: harder than a resting contact
    // presses when struck from above, at all from the side, and from below
    // however slowly when the mover is driven into it (its acceleration, with
    // gravity and held support, points up at it) and would have gone in by more
    // than the slop: it would rest on a moving body (see separate()). A body of a
    // pile that rises a hair after a push is no such press; waking on it woke
    // whole columns of a sleeping pile, again and again.
    if (body(hit_body).is_dynamic()) {
      Vec2 travel{};
      component(travel, axis) = path.x0 > level ? -1.0 : 1.0;
      const double rising = dot(c_.up, travel);
      const bool driven = path.a * component(travel, axis) > 0.0;
      const bool from_below =
          c_.gravity_on && rising > 0.0 && driven && std::fabs(path.x1 - level) > s_.slop;
      if (from_below || std::fabs(v_hit) > wake_speed(rising < 0.0)) {
        x_.to_wake.push_back(hit_body);
      }
    }
    const double v_out =
        -effective_restitution(std::fabs(v_hit), restitution, c_.rest_speed) * v_hit;
    const double left = path.h - first_t;
    if (v_out == 0.0) {
      // Resting contact: stay where it touched, a few ulps inside so the contact
      // is surely found, and keep the approach velocity: the velocity solver
      // removes it with an impulse, which is what contact friction is bounded by.
      const double inside = path.x0 > level ? -kInfinity : kInfinity;
      double touching = level;
      for (int ulp = 0; ulp < 4; ++ulp) touching = std::nextafter(touching, inside);
      // The velocity kept is the free motion's at the end of the step: all that
      // acceleration pressed into the support over the step, not just until impact.
      const double pressed = (path.v1 > 0.0) == (v_hit > 0.0) ? path.v1 : v_hit;
      path = {path.integrator, touching, pressed, 0.0, 0.0, left, touching, pressed};
      // The contact is recorded here, with its true normal: on a curved surface
      // (a circle, a box's corner) the move on the other axis can leave the shapes
      // a hair apart, and a contact found only by overlap would then be missed,
      // the pressed velocity never removed, and the body would hang on the curve
      // gathering speed instead of sliding off it.
      component(b.position, axis) = touching;
      const Vec2 n = touching_normal(b, body(hit_body), axis, inside < 0.0 ? -1.0 : 1.0);
      record_contact(hit_candidate, n);
      return;
    }
    const AxisMotion rest =
        path.integrator == Integrator::Exact
            ? integrate_axis(Integrator::Exact, level, v_out, path.a, path.k, left)
            : AxisMotion{level + v_out * left, v_out};
    path = {path.integrator, level, v_out, path.a, path.k, left, rest.position, rest.velocity};
  }
}

// The unit normal from `mover` toward `obstacle` where they touch: the narrowphase
// formulas' normal (line of centres, or a circle's centre to the nearest point of
// a box), asked with a radius that always reaches; for two faces, along the swept
// axis in the direction of travel (`toward`).
inline Vec2 MovePass::touching_normal(const Body& mover, const Body& obstacle, int axis,
                                      double toward) {
  if (mover.shape == Shape::Circle && obstacle.shape == Shape::Circle) {
    return collide_circles(mover.position, kInfinity, obstacle.position, 0.0).normal;
  }
  if (mover.shape == Shape::Circle) {
    return collide_circle_box(mover.position, kInfinity, obstacle.bounds()).normal;
  }
  if (obstacle.shape == Shape::Circle) {
    return -collide_circle_box(obstacle.position, kInfinity, mover.bounds()).normal;
  }
  Vec2 along{};
  component(along, axis) = toward;
  return along;
}

}  // namespace

// Move every awake body along one axis. Against static and sleeping bodies the
// move is swept: it stops at the time of impact, bounces, and goes on.
void move_on_axis(const StepContext& ctx, WorldImpl& w, int axis) {
  MovePass(ctx, w).run(axis, axis);
}

// With no awake box there is no collision on Y between the moves: each body moves
// on Y and then on X in one walk over the bodies instead of two. The result is the
// two walks' bit for bit, because a body's moves read no other awake body (the
// sweep meets static and sleeping bodies only), and a walk over bodies scattered
// in memory costs as much as the moves themselves.
void move_both_axes(const StepContext& ctx, WorldImpl& w) { MovePass(ctx, w).run(1, 0); }

}  // namespace phys
