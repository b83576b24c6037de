// Free motion of the awake bodies over a sub-step (friction, acceleration, gravity,
// the speed limit), and the candidate pairs their boxes can reach in it.
// Reads: the bodies, the processing order, the fixed bodies' boxes and grid.
// Writes: scratch.motion and scratch.broadphase; the bodies' corrections (reset);
// the candidate pairs (WorldImpl::candidates), kept while every body stays inside
// its fat box.
#include <algorithm>
#include <cmath>
#include <utility>

#include "step_phases.h"
#include "step_shared.h"

namespace phys {

namespace {

// Pairs are found with boxes grown by this fraction more (of a body's smaller half
// extent), and reused while every body stays inside its grown box.
constexpr double kFatMargin = 0.1;
// Up to this many static and sleeping bodies are tested one by one, not through
// their grid.
constexpr std::size_t kFewFixed = 8;

// What a body may reach this sub-step, given its free-motion displacement d:
// beyond its own motion, a body can be pushed by its neighbours while contacts
// are resolved, and a tenth of its size keeps those pushes within the pairs found.
inline Aabb needed_box(const Body& b, Vec2 d, double slop) {
  const double pushed = kPushMargin * std::min(b.half.x, b.half.y) + slop;
  const Vec2 margin{std::fabs(d.x) + pushed, std::fabs(d.y) + pushed};
  Aabb box = b.bounds();
  box.min -= margin;
  box.max += margin;
  return box;
}

// The box a body's pairs are found with: what it needs, grown so that the pairs
// may be kept while it stays inside (see FreeMotionPass::run).
inline Aabb fattened(const Body& b, const Aabb& needed) {
  const double extra = kFatMargin * std::min(b.half.x, b.half.y);
  return {needed.min - Vec2{extra, extra}, needed.max + Vec2{extra, extra}};
}

class FreeMotionPass : StepPhase {
 public:
  FreeMotionPass(const StepContext& ctx, WorldImpl& world, const Order& order)
      : StepPhase(ctx, world), order_(order) {}
  // Friction, acceleration and gravity: the free motion of each awake body over the
  // sub-step, per axis (scratch.motion). The moves (step_moves.cpp) apply it.
  FreeMotion run() {
    if (order_.scattered) return run<true>();
    return run<false>();
  }
  void find_candidates(const FreeMotion& motion);

 private:
  template <bool kPrefetch>
  FreeMotion run();
  // The candidate pairs from the grids' overlaps; with kFilter, only the pairs that
  // may collide (filters, sensors). Built apart, so that a world without filters
  // carries no trace of the test.
  template <bool kFilter>
  void collect_candidates();
  void renumber_candidates();

  Order order_;
};

// In two builds, as resolve_passes: with prefetching for bodies scattered in
// memory, and without it, so that a stack's loop carries no trace of it. Measured
// against one instance (bench/compare-core.sh, thread CPU time per step): never
// prefetching, rain-16000 ran 1.052x (sleep on) / 1.083x (off); always, the awake
// pyramid-5050 ran 1.008x, 1.7% over the run-to-run noise's mean.
// Long on purpose: one walk over the awake bodies integrates, caps speeds and checks
// the pairs' reuse while each body is in cache; split, each part would walk them again.
template <bool kPrefetch>
inline FreeMotion FreeMotionPass::run() {
  const std::size_t n = w_.lists.active.size();
  x_.motion.velocity.resize(n);
  x_.motion.displacement.resize(n);
  bool any_friction = false;
  bool any_contact_friction = false;
  // The broadphase's reuse check rides along (it reads the same body and the
  // displacement just computed): every body still inside the box its pairs were
  // found with, and those pairs are still a superset of the ones that can touch
  // (Box2D's fat boxes). The first body outside ends it. The order may have
  // changed: each body's box is then found at its old position.
  bool all_inside = w_.candidates.valid && (!order_.changed || order_.from_known) &&
                    w_.candidates.fat_boxes.size() == n;
  const std::uint32_t* const was_at = order_.from_known ? x_.order.from.data() : nullptr;
  // Once the pairs are sure to be found anew (the lists changed, or a body left its
  // box, as in every step of a flowing pile), the boxes they will be found with are
  // made here, while the body is in cache. A resting stack, whose pairs are kept,
  // pays nothing.
  std::size_t fat_from = all_inside ? n : 0;  // next_fat_boxes are made from here on
  auto& next_fat = x_.motion.next_fat_boxes;
  next_fat.resize(n);
  bool any_box = false;
  bool any_circle = false;
  for (std::size_t p = 0; p < n; ++p) {
    if (kPrefetch) prefetch_ahead(p);
    Body& b = body(w_.lists.active[p]);
    b.correction = {};
    any_friction = any_friction || b.friction.x != 0.0 || b.friction.y != 0.0;
    any_contact_friction = any_contact_friction || b.contact_friction > 0.0;
    any_box = any_box || b.shape == Shape::Box;
    any_circle = any_circle || b.shape == Shape::Circle;
    const Vec2 a = driving_acceleration(b);
    const AxisMotion mx =
        integrate_axis(s_.integrator, b.position.x, b.velocity.x, a.x, b.friction.x, c_.h);
    const AxisMotion my =
        integrate_axis(s_.integrator, b.position.y, b.velocity.y, a.y, b.friction.y, c_.h);
    Vec2 v{mx.velocity, my.velocity};
    Vec2 d{mx.position - b.position.x, my.position - b.position.y};
    // A resting body moves as if its contacts still held it (it does not sink
    // into its support, nor creep along it when friction holds a push), but its
    // velocity keeps all of its acceleration: the contacts must take that away
    // again, which is how the next step knows they are there.
    if (b.held.x != 0.0) {
      d.x = integrate_axis(s_.integrator, b.position.x, b.velocity.x, a.x + b.held.x, b.friction.x,
                           c_.h)
                .position -
            b.position.x;
    }
    if (b.held.y != 0.0) {
      d.y = integrate_axis(s_.integrator, b.position.y, b.velocity.y, a.y + b.held.y, b.friction.y,
                           c_.h)
                .position -
            b.position.y;
    }
    // A squared speed below a quarter of the limit's square is surely under the
    // limit (sqrt of it is about half the limit): no square root for the usual body.
    const double speed_squared = dot(v, v);
    double speed = speed_squared <= c_.surely_slow ? 0.0 : std::sqrt(speed_squared);
    // The square overflows past about 1.3e154 m/s; under a max_speed above that, the
    // speed is measured again without squaring.
    if (speed > s_.max_speed && std::isinf(speed)) speed = length_without_overflow(v);
    if (speed > s_.max_speed) {  // the world stays finite: speeds are capped
      const double scale = s_.max_speed / speed;
      v = v * scale;
      d = d * scale;
      ++w_.counters.speed_clamps;
    }
    x_.motion.velocity[p] = v;
    x_.motion.displacement[p] = d;
    if (all_inside) {
      const Aabb needed = needed_box(b, d, s_.slop);
      const Aabb& fat = w_.candidates.fat_boxes[was_at != nullptr ? was_at[p] : p];
      all_inside = needed.min.x >= fat.min.x && needed.min.y >= fat.min.y &&
                   needed.max.x <= fat.max.x && needed.max.y <= fat.max.y;
      if (!all_inside) {
        fat_from = p;
        next_fat[p] = fattened(b, needed);
      }
    } else {  // from fat_from on
      next_fat[p] = fattened(b, needed_box(b, d, s_.slop));
    }
  }
  w_.counters.bodies_integrated += n;
  if (any_contact_friction) {
    x_.motion.step_start.resize(n);
    for (std::size_t p = 0; p < n; ++p) x_.motion.step_start[p] = body(w_.lists.active[p]).position;
  }
  if (any_friction) ++w_.counters.friction_passes;
  if (c_.gravity_on) ++w_.counters.gravity_passes;
  return {all_inside, fat_from, any_box, any_circle, any_contact_friction};
}

// Candidate pairs for the whole sub-step: boxes fattened by how far each body can
// move in it, so the pairs hold for both axis moves.
void FreeMotionPass::find_candidates(const FreeMotion& motion) {
  if (motion.all_inside) {  // run() found the last pairs still good (fat boxes)
    if (order_.changed) {
      renumber_candidates();
      ++w_.counters.broadphase_renumbers;
    }
    ++w_.counters.broadphase_reuses;
    return;
  }
  // The last pairs looked reusable until the body at fat_from left its box: the
  // boxes before it are made now.
  auto& fat = w_.candidates.fat_boxes;
  fat.swap(x_.motion.next_fat_boxes);
  for (std::size_t p = 0; p < motion.fat_from; ++p) {
    if (order_.scattered) prefetch_ahead(p);
    const Body& b = body(w_.lists.active[p]);
    fat[p] = fattened(b, needed_box(b, x_.motion.displacement[p], s_.slop));
  }
  x_.broadphase.active_grid.build(fat);
  x_.broadphase.active_grid.find_pairs(x_.broadphase.active_pairs);

  // Pairs that may not collide (filters, sensors) are left out here, so that no
  // later phase meets them.
  if (w_.filtering()) {
    collect_candidates<true>();
  } else {
    collect_candidates<false>();
  }
}

template <bool kFilter>
inline void FreeMotionPass::collect_candidates() {
  const std::size_t n = w_.lists.active.size();
  const auto& fat = w_.candidates.fat_boxes;
  w_.candidates.list.clear();
  w_.candidates.first.assign(n + 1, 0);
  const bool few_fixed = w_.lists.fixed_boxes.size() <= kFewFixed;
  std::size_t next_pair = 0;
  for (std::uint32_t p = 0; p < n; ++p) {
    w_.candidates.first[p] = static_cast<std::uint32_t>(w_.candidates.list.size());
    if (few_fixed) {
      // A handful of static bodies (a container's walls): testing each is cheaper
      // than a grid query, and gives the same ones in the same (ascending) order.
      for (std::uint32_t f = 0; f < w_.lists.fixed_boxes.size(); ++f) {
        if (boxes_intersect(fat[p], w_.lists.fixed_boxes[f])) {
          if (kFilter && !w_.pair_collides(w_.lists.active[p], w_.lists.fixed[f])) continue;
          w_.candidates.list.push_back({w_.lists.active[p], w_.lists.fixed[f], p, kNone, true});
        }
      }
    } else if (w_.lists.fixed_grid.size() > 0) {
      w_.lists.fixed_grid.find_overlaps(fat[p], x_.broadphase.overlaps);
      for (std::uint32_t f : x_.broadphase.overlaps) {
        if (kFilter && !w_.pair_collides(w_.lists.active[p], w_.lists.fixed[f])) continue;
        w_.candidates.list.push_back({w_.lists.active[p], w_.lists.fixed[f], p, kNone, true});
      }
    }
    while (next_pair < x_.broadphase.active_pairs.size() &&
           x_.broadphase.active_pairs[next_pair].a == p) {
      const std::uint32_t q = x_.broadphase.active_pairs[next_pair].b;
      if (!kFilter || w_.pair_collides(w_.lists.active[p], w_.lists.active[q])) {
        w_.candidates.list.push_back({w_.lists.active[p], w_.lists.active[q], p, q, false});
      }
      ++next_pair;
    }
  }
  w_.candidates.first[n] = static_cast<std::uint32_t>(w_.candidates.list.size());
  w_.candidates.valid = true;
}

// The pairs are kept but the order changed: each pair takes its bodies' new
// positions (the earlier one its lower body), and the list is regrouped as
// collect_candidates would list the same fat boxes in the new order (grouped by
// the lower body's position; in a group the static and sleeping bodies first, as
// they were, then the awake ones by position), so that what follows cannot tell a
// kept list from a new one. A counting sort by the lower position and an
// insertion sort of each group (a handful of pairs): linear in the pairs.
void FreeMotionPass::renumber_candidates() {
  const std::size_t n = w_.lists.active.size();
  const auto& from = x_.order.from;
  auto& now = x_.broadphase.position_now;
  now.resize(n);
  for (std::uint32_t p = 0; p < n; ++p) now[from[p]] = p;
  auto& fat = w_.candidates.fat_boxes;
  auto& moved = x_.motion.next_fat_boxes;
  moved.resize(n);
  for (std::size_t p = 0; p < n; ++p) moved[p] = fat[from[p]];
  fat.swap(moved);

  auto& list = w_.candidates.list;
  auto& first = w_.candidates.first;
  first.assign(n + 1, 0);
  for (Candidate& c : list) {
    c.lower_pos = now[c.lower_pos];
    if (!c.fixed) {
      c.upper_pos = now[c.upper_pos];
      if (c.upper_pos < c.lower_pos) {
        std::swap(c.lower, c.upper);
        std::swap(c.lower_pos, c.upper_pos);
      }
    }
    ++first[c.lower_pos + 1];
  }
  for (std::size_t p = 0; p < n; ++p) first[p + 1] += first[p];
  auto& regrouped = x_.broadphase.regrouped;
  regrouped.resize(list.size());
  for (const Candidate& c : list) regrouped[first[c.lower_pos]++] = c;
  // first[p] is now the end of group p: shift it back to the starts.
  for (std::size_t p = n; p > 0; --p) first[p] = first[p - 1];
  first[0] = 0;
  const auto goes_before = [](const Candidate& a, const Candidate& b) {
    return !b.fixed && (a.fixed || a.upper_pos < b.upper_pos);
  };
  for (std::size_t p = 0; p < n; ++p) {
    for (std::uint32_t k = first[p] + 1; k < first[p + 1]; ++k) {
      const Candidate c = regrouped[k];
      std::uint32_t m = k;
      while (m > first[p] && goes_before(c, regrouped[m - 1])) {
        regrouped[m] = regrouped[m - 1];
        --m;
      }
      regrouped[m] = c;
    }
  }
  list.swap(regrouped);
}

}  // namespace

FreeMotion integrate(const StepContext& ctx, WorldImpl& w, const Order& order) {
  return FreeMotionPass(ctx, w, order).run();
}

void find_candidates(const StepContext& ctx, WorldImpl& w, const Order& order,
                     const FreeMotion& motion) {
  FreeMotionPass(ctx, w, order).find_candidates(motion);
}

}  // namespace phys
