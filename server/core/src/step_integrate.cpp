// Free motion of the awake bodies over a sub-step (friction, acceleration, gravity,
// the speed limit), and the candidate pairs their boxes can reach in it.
#include <cmath>

#include "phase_timer.h"
#include "step_runner.h"

namespace phys {

// Friction, acceleration and gravity: the free motion of each awake body over the
// sub-step, per axis. The moves (step_moves.cpp) apply it.
void StepRunner::integrate() {
  if (scattered_) {
    integrate<true>();
  } else {
    integrate<false>();
  }
}

// In two builds, as resolve_passes: with prefetching for bodies scattered in
// memory, and without it, so that a stack's loop carries no trace of it.
template <bool kPrefetch>
inline void StepRunner::integrate() {
  const std::size_t n = w_.active_.size();
  w_.step_velocity_.resize(n);
  w_.step_displacement_.resize(n);
  bool any_friction = false;
  any_contact_friction_ = false;
  // The broadphase's reuse check rides along (it reads the same body and the
  // displacement just computed): every body still inside the box its pairs were
  // found with, in the same order, and those pairs are still a superset of the
  // ones that can touch (Box2D's fat boxes). The first body outside ends it.
  bool all_inside = w_.candidates_valid_ && !order_changed_ && w_.fat_boxes_.size() == n;
  // When the pairs are sure to be found anew (the order or the lists changed, as in
  // every step of a flowing pile), the boxes they will be found with are made here,
  // while the body is in cache. A resting stack, whose pairs are kept, pays nothing.
  fat_made_ = !all_inside;
  auto& next_fat = w_.next_fat_boxes_;
  if (fat_made_) next_fat.resize(n);
  any_active_box_ = false;
  any_active_circle_ = false;
  for (std::size_t p = 0; p < n; ++p) {
    if (kPrefetch) prefetch_ahead(p);
    Body& b = body(w_.active_[p]);
    b.correction = {};
    any_friction = any_friction || b.friction.x != 0.0 || b.friction.y != 0.0;
    any_contact_friction_ = any_contact_friction_ || b.contact_friction > 0.0;
    any_active_box_ = any_active_box_ || b.shape == Shape::Box;
    any_active_circle_ = any_active_circle_ || b.shape == Shape::Circle;
    const Vec2 a = driving_acceleration(b);
    const AxisMotion mx =
        integrate_axis(s_.integrator, b.position.x, b.velocity.x, a.x, b.friction.x, h_);
    const AxisMotion my =
        integrate_axis(s_.integrator, b.position.y, b.velocity.y, a.y, b.friction.y, h_);
    Vec2 v{mx.velocity, my.velocity};
    Vec2 d{mx.position - b.position.x, my.position - b.position.y};
    // A resting body moves as if its contacts still held it (it does not sink
    // into its support, nor creep along it when friction holds a push), but its
    // velocity keeps all of its acceleration: the contacts must take that away
    // again, which is how the next step knows they are there.
    if (b.held.x != 0.0) {
      d.x = integrate_axis(s_.integrator, b.position.x, b.velocity.x, a.x + b.held.x, b.friction.x,
                           h_)
                .position -
            b.position.x;
    }
    if (b.held.y != 0.0) {
      d.y = integrate_axis(s_.integrator, b.position.y, b.velocity.y, a.y + b.held.y, b.friction.y,
                           h_)
                .position -
            b.position.y;
    }
    // A squared speed below a quarter of the limit's square is surely under the
    // limit (sqrt of it is about half the limit): no square root for the usual body.
    const double speed_squared = dot(v, v);
    double speed = speed_squared <= surely_slow_ ? 0.0 : std::sqrt(speed_squared);
    // The square overflows past about 1.3e154 m/s; under a max_speed above that, the
    // speed is measured again without squaring.
    if (speed > s_.max_speed && std::isinf(speed)) speed = length_without_overflow(v);
    if (speed > s_.max_speed) {  // the world stays finite: speeds are capped
      const double scale = s_.max_speed / speed;
      v = v * scale;
      d = d * scale;
      ++w_.counters.speed_clamps;
    }
    w_.step_velocity_[p] = v;
    w_.step_displacement_[p] = d;
    if (fat_made_) {
      next_fat[p] = fattened(b, needed_box(b, d));
    } else if (all_inside) {
      const Aabb box = needed_box(b, d);
      const Aabb& fat = w_.fat_boxes_[p];
      all_inside = box.min.x >= fat.min.x && box.min.y >= fat.min.y && box.max.x <= fat.max.x &&
                   box.max.y <= fat.max.y;
    }
  }
  all_inside_ = all_inside;
  w_.counters.bodies_integrated += n;
  if (any_contact_friction_) {
    w_.step_start_.resize(n);
    for (std::size_t p = 0; p < n; ++p) w_.step_start_[p] = body(w_.active_[p]).position;
  }
  if (any_friction) ++w_.counters.friction_passes;
  if (gravity_on_) ++w_.counters.gravity_passes;
}

// What a body may reach this sub-step, given its free-motion displacement d:
// beyond its own motion, a body can be pushed by its neighbours while contacts
// are resolved, and a tenth of its size keeps those pushes within the pairs found.
inline Aabb StepRunner::needed_box(const Body& b, Vec2 d) const {
  const double pushed = kPushMargin * std::min(b.half.x, b.half.y) + s_.slop;
  const Vec2 margin{std::fabs(d.x) + pushed, std::fabs(d.y) + pushed};
  Aabb box = b.bounds();
  box.min -= margin;
  box.max += margin;
  return box;
}

// The box a body's pairs are found with: what it needs, grown so that the pairs
// may be kept while it stays inside (see integrate()).
inline Aabb StepRunner::fattened(const Body& b, const Aabb& needed) {
  const double extra = kFatMargin * std::min(b.half.x, b.half.y);
  return {needed.min - Vec2{extra, extra}, needed.max + Vec2{extra, extra}};
}

// Candidate pairs for the whole sub-step: boxes fattened by how far each body can
// move in it, so the pairs hold for both axis moves.
void StepRunner::find_candidates() {
  const std::size_t n = w_.active_.size();
  if (all_inside_) {  // integrate() found the last pairs still good (fat boxes)
    ++w_.counters.broadphase_reuses;
    return;
  }
  auto& fat = w_.fat_boxes_;
  if (fat_made_) {
    fat.swap(w_.next_fat_boxes_);
  } else {  // the last pairs looked reusable until a body left its box
    fat.resize(n);
    for (std::size_t p = 0; p < n; ++p) {
      if (scattered_) prefetch_ahead(p);
      const Body& b = body(w_.active_[p]);
      fat[p] = fattened(b, needed_box(b, w_.step_displacement_[p]));
    }
  }
  w_.active_grid_.build(fat);
  w_.active_grid_.find_pairs(w_.active_pairs_);

  w_.candidates_.clear();
  w_.first_candidate_.assign(n + 1, 0);
  const bool few_fixed = w_.fixed_boxes_.size() <= kFewFixed;
  std::size_t next_pair = 0;
  for (std::uint32_t p = 0; p < n; ++p) {
    w_.first_candidate_[p] = static_cast<std::uint32_t>(w_.candidates_.size());
    if (few_fixed) {
      // A handful of static bodies (a container's walls): testing each is cheaper
      // than a grid query, and gives the same ones in the same (ascending) order.
      for (std::uint32_t f = 0; f < w_.fixed_boxes_.size(); ++f) {
        if (boxes_intersect(fat[p], w_.fixed_boxes_[f])) {
          w_.candidates_.push_back({w_.active_[p], w_.fixed_[f], p, kNone, true});
        }
      }
    } else if (w_.fixed_grid_.size() > 0) {
      w_.fixed_grid_.find_overlaps(fat[p], w_.overlaps_);
      for (std::uint32_t f : w_.overlaps_) {
        w_.candidates_.push_back({w_.active_[p], w_.fixed_[f], p, kNone, true});
      }
    }
    while (next_pair < w_.active_pairs_.size() && w_.active_pairs_[next_pair].a == p) {
      const std::uint32_t q = w_.active_pairs_[next_pair].b;
      w_.candidates_.push_back({w_.active_[p], w_.active_[q], p, q, false});
      ++next_pair;
    }
  }
  w_.first_candidate_[n] = static_cast<std::uint32_t>(w_.candidates_.size());
  w_.candidates_valid_ = true;
}

}  // namespace phys
