// The position passes: overlapping pairs pushed apart by penetration plus slop
// (boxes one axis at a time, circles along their normal), with shock propagation,
// static friction, and the contacts and near misses the velocity solver needs.
// Reads: the candidates, the bodies, scratch.motion.step_start (static friction).
// Writes: the bodies' positions and corrections; scratch.marks, supported,
// position and to_wake.
#include <algorithm>
#include <cmath>

#include "step_phases.h"
#include "step_shared.h"

namespace phys {

namespace {

// A normal this close to gravity's line is a face resting on a face.
constexpr double kAlongGravity = 1.0 - 1.0e-9;

inline void prefetch_pair(const Body* bodies, const Candidate& cand) {
  __builtin_prefetch(&bodies[cand.lower]);
  __builtin_prefetch(&bodies[cand.upper]);
}

class PositionPass : StepPhase {
 public:
  PositionPass(const StepContext& ctx, WorldImpl& world, const Order& order,
               const FreeMotion& motion)
      : StepPhase(ctx, world),
        order_(order),
        motion_(motion),
        pins_(world.kinematic_count() != 0 && !world.scratch.position.pinned.empty()) {}
  template <int axis>
  void collide_boxes_on();
  void collide_with_circles();

 private:
  template <bool kPrefetch>
  void relaxed_circle_passes();
  bool resolve_circle_pair(const Candidate& cand, Body& a, Body& b, Vec2 n, double depth,
                           bool corner);
  bool collide_circle_pair(const Candidate& cand, Body& a, Body& b, double grown,
                           std::uint64_t& circle_tests, std::uint64_t& mixed_tests);
  double near_gap(const Body& a, const Body& b) const;
  bool near(const Body& a, const Body& b) const;
  template <typename Resolve>
  void resolve_passes(Resolve&& resolve);
  template <bool kPrefetch, typename Resolve>
  void resolve_passes(Resolve& resolve);
  bool separate(const Candidate& cand, Body& a, Body& b, Vec2 n, double depth);
  void hold_by_static_friction(const Candidate& cand, Body& a, Body& b, Vec2 n, double push,
                               double wa, double wb);
  bool may_undo_slide(const Body& body, Vec2 undo) const;
  void record_near_miss(const Candidate& cand, Vec2 n, double gap);
  bool held_off(const Candidate& cand, const Body& b, Vec2 n) const;

  Order order_;
  FreeMotion motion_;
  const bool pins_;  // some body is pinned (find_pinned_bodies)
};

// How close two bodies must be after the first pass to be worth another: within
// the push margin of each other.
inline double PositionPass::near_gap(const Body& a, const Body& b) const {
  return kPushMargin * std::min(std::min(a.half.x, a.half.y), std::min(b.half.x, b.half.y)) +
         s_.slop;
}

inline bool PositionPass::near(const Body& a, const Body& b) const {
  const double gap = near_gap(a, b);
  Aabb grown = a.bounds();
  grown.min -= Vec2{gap, gap};
  grown.max += Vec2{gap, gap};
  return boxes_intersect(grown, b.bounds());
}

// Gauss-Seidel passes over the candidate pairs: the first pass visits all of them
// and keeps the pairs near enough to matter; later passes visit only those.
// The passes come in two builds: with prefetching for bodies scattered in
// memory, and without it, so that a stack's loop carries no trace of it. Measured
// against one instance (bench/compare-core.sh, thread CPU time per step): never
// prefetching, rain-16000 ran 1.28x (sleep on) / 1.41x (off); always, the awake
// pyramid-5050 ran 1.022x, 3% over the run-to-run noise's mean. The pair
// tests given to it (the lambdas below) are forced inline: each is the loop's body,
// and the compiler's own budget, spent on the passes inlined into their phase,
// left a call per pair.
template <typename Resolve>
inline void PositionPass::resolve_passes(Resolve&& resolve) {
  if (order_.scattered) {
    resolve_passes<true>(resolve);
  } else {
    resolve_passes<false>(resolve);
  }
}

template <bool kPrefetch, typename Resolve>
inline void PositionPass::resolve_passes(Resolve& resolve) {
  auto& near_list = x_.position.near_candidates;
  const auto candidates = static_cast<std::uint32_t>(w_.candidates.list.size());
  near_list.resize(candidates);  // filled by index: no growth check per pair
  // The arrays by plain pointers: a push marks support through a byte store,
  // which may alias anything, and would make each pair reload them.
  std::uint32_t* const listed = near_list.data();
  const Candidate* const cands = w_.candidates.list.data();
  Body* const bodies = w_.bodies.data();
  std::uint32_t near_count = 0;
  for (int iteration = 0; iteration < s_.position_iterations; ++iteration) {
    x_.supported.assign(w_.lists.active.size(), 0);
    bool moved = false;
    if (iteration == 0) {
      for (std::uint32_t c = 0; c < candidates; ++c) {
        const Candidate& cand = cands[c];
        if (kPrefetch && c + kPrefetchAhead < candidates) {
          prefetch_pair(bodies, cands[c + kPrefetchAhead]);
        }
        Body& a = bodies[cand.lower];
        Body& b = bodies[cand.upper];
        if (!near(a, b)) continue;
        listed[near_count++] = c;
        moved = resolve(cand, a, b) || moved;
      }
    } else {
      for (std::uint32_t k = 0; k < near_count; ++k) {
        const Candidate& cand = cands[listed[k]];
        if (kPrefetch && k + kPrefetchAhead < near_count) {
          prefetch_pair(bodies, cands[listed[k + kPrefetchAhead]]);
        }
        moved = resolve(cand, bodies[cand.lower], bodies[cand.upper]) || moved;
      }
    }
    if (!moved) break;
  }
}

// Per-axis resolution of box pairs: the recipe's penetration on the axis, pushed
// apart by penetration plus slop, up if above, down if below. The axis is a
// template argument: picking a component by a run-time axis cost a branch per
// use, and the registers those branches tied up spilled the pair loop's state.
template <int axis>
inline void PositionPass::collide_boxes_on() {
  constexpr int other = 1 - axis;
  const Vec2 unit = axis == 0 ? Vec2{1.0, 0.0} : Vec2{0.0, 1.0};
  std::uint64_t tests = 0;  // counted here, added once: the loop keeps it in a register
  resolve_passes([&](const Candidate& cand, Body& a, Body& b) __attribute__((always_inline)) {
    if (a.shape != Shape::Box || b.shape != Shape::Box) return false;
    ++tests;
    const Aabb ba = a.bounds();
    const Aabb bb = b.bounds();
    // Touching on the other axis only (side by side): that axis resolves it.
    const double across = std::min(component(ba.max, other), component(bb.max, other)) -
                          std::max(component(ba.min, other), component(bb.min, other));
    if (across <= 0.5 * s_.slop) return false;
    const double ca = component(a.position, axis);
    const double cb = component(b.position, axis);
    const Vec2 n = (cb >= ca) ? unit : -unit;  // from a toward b
    const double gap = std::min(component(ba.max, axis), component(bb.max, axis)) -
                       std::max(component(ba.min, axis), component(bb.min, axis));
    if (gap < 0.0) {  // apart on this axis: a near miss, or nothing
      // Two dynamic boxes side by side (across gravity) fall together and carry
      // nothing of each other: their near miss would only add work to a stack's
      // velocity pass (a third of it in the 5,050-box pyramid).
      const bool side_by_side = !cand.fixed && std::fabs(dot(n, c_.up)) < 1.0 - kAlongGravity;
      if (-gap <= near_miss_margin() && !side_by_side) record_near_miss(cand, n, -gap);
      return false;
    }
    const double depth = axis_penetration(ca, component(a.half, axis), cb, component(b.half, axis));
    // Resolve on this axis only if it is the shallower one. Otherwise a box that
    // sank a little into a floor tile would be thrown sideways by the tile's
    // width (catching on seams), or lifted by a neighbour's height.
    if (depth > across) return false;
    return separate(cand, a, b, n, depth);
  });
  w_.counters.box_box_tests += tests;
}

// The narrowphase of a pair with a circle, its shapes grown by `grown`: the
// contact (normal from a toward b), whether it is a circle beside a box's corner,
// and false when neither body is a circle (a box pair, resolved per axis).
inline bool collide_grown(const Body& a, const Body& b, double grown, Contact& contact,
                          bool& corner, std::uint64_t& circle_tests, std::uint64_t& mixed_tests) {
  corner = false;
  if (a.shape == Shape::Circle && b.shape == Shape::Circle) {
    ++circle_tests;
    contact = collide_circles(a.position, a.radius + grown, b.position, b.radius);
  } else if (a.shape == Shape::Circle) {
    ++mixed_tests;
    contact = collide_circle_box(a.position, a.radius + grown, b.bounds());
    corner = contact.normal.x != 0.0 && contact.normal.y != 0.0;
  } else if (b.shape == Shape::Circle) {
    ++mixed_tests;
    contact = collide_circle_box(b.position, b.radius + grown, a.bounds());
    contact.normal = -contact.normal;
    corner = contact.normal.x != 0.0 && contact.normal.y != 0.0;
  } else {
    return false;
  }
  return true;
}

// Every pair with a circle, along its normal (a circle's normal needs no axis
// split).
void PositionPass::collide_with_circles() {
  if (s_.relaxed_position_passes) {
    if (order_.scattered) {
      relaxed_circle_passes<true>();
    } else {
      relaxed_circle_passes<false>();
    }
    return;
  }
  std::uint64_t circle_tests = 0;
  std::uint64_t mixed_tests = 0;
  const double grown = near_miss_margin() + c_.speculative_margin;
  resolve_passes([&](const Candidate& cand, Body& a, Body& b) __attribute__((always_inline)) {
    return collide_circle_pair(cand, a, b, grown, circle_tests, mixed_tests);
  });
  w_.counters.circle_circle_tests += circle_tests;
  w_.counters.circle_box_tests += mixed_tests;
}

// The narrowphase and resolution of a pair with a circle; false for a box pair.
__attribute__((always_inline)) inline bool PositionPass::collide_circle_pair(
    const Candidate& cand, Body& a, Body& b, double grown, std::uint64_t& circle_tests,
    std::uint64_t& mixed_tests) {
  Contact contact;
  bool corner = false;
  if (!collide_grown(a, b, grown, contact, corner, circle_tests, mixed_tests)) return false;
  if (!contact.colliding) return false;
  return resolve_circle_pair(cand, a, b, contact.normal, contact.penetration - grown, corner);
}

// Shapes are tested grown by the near-miss margin: a pair a hair apart (as the
// last push left it) is still a contact for the velocity pass. Circle pairs and
// a circle facing a box's face are grown by the speculative margin too (see
// StepContext::speculative_margin); a circle beside a box's corner is not: the corner of
// the next tile of a floor is where a rolling circle would catch on a seam.
// depth: the penetration of the grown shapes less the growth (below 0: apart).
inline bool PositionPass::resolve_circle_pair(const Candidate& cand, Body& a, Body& b, Vec2 n,
                                              double depth, bool corner) {
  if (depth < 0.0) {
    if (corner && -depth > near_miss_margin()) return false;
    record_near_miss(cand, n, -depth);
    return false;
  }
  return separate(cand, a, b, n, depth);
}

// The circle pairs' passes, relaxed: the first kCapturePass + 1 passes run the
// narrowphase on every near pair, and the last of them keeps, for each pair that
// touches, its normal and the base of its penetration; later passes find that
// penetration again from the bodies' moves along the normal alone, which is exact
// for a pair moving along its normal and otherwise a first-order estimate that
// overstates it (a push a little too far, never too short, for two circles). Near
// pairs that did not touch then keep the full narrowphase.
//
// The normals are kept from the second pass, not the first: before the first pass
// the pairs are still as deep as the free motion left them, and normals kept then
// left the rains' largest overlap at 0.0055 m (rain-1000) and 0.0063 m (rain-4000),
// over the 0.005 m bound, against 0.0042 and 0.0033 m kept from the second
// (docs/ACCURACY.md, "Relaxed position passes").
constexpr int kCapturePass = 1;

template <bool kPrefetch>
void PositionPass::relaxed_circle_passes() {
  std::uint64_t circle_tests = 0;
  std::uint64_t mixed_tests = 0;
  std::uint64_t relaxed_updates = 0;
  const double grown = near_miss_margin() + c_.speculative_margin;
  auto& relaxed_list = x_.position.relaxed;
  auto& near_list = x_.position.near_candidates;
  const auto candidates = static_cast<std::uint32_t>(w_.candidates.list.size());
  relaxed_list.resize(candidates);
  near_list.resize(candidates);
  StepScratch::Position::RelaxedPair* const relaxed = relaxed_list.data();
  std::uint32_t* const listed = near_list.data();
  const Candidate* const cands = w_.candidates.list.data();
  Body* const bodies = w_.bodies.data();
  std::uint32_t relaxed_count = 0;
  std::uint32_t near_count = 0;
  // The pass that keeps each touching pair's normal: pairs that do not touch stay in
  // `listed` (compacted in place) for the narrowphase.
  auto capture = [&](std::uint32_t c, std::uint32_t & kept) __attribute__((always_inline)) {
    const Candidate& cand = cands[c];
    Body& a = bodies[cand.lower];
    Body& b = bodies[cand.upper];
    Contact contact;
    bool corner = false;
    if (!collide_grown(a, b, grown, contact, corner, circle_tests, mixed_tests)) return false;
    if (!contact.colliding) {
      listed[kept++] = c;
      return false;
    }
    const Vec2 n = contact.normal;
    const double depth = contact.penetration - grown;
    relaxed[relaxed_count++] = {n, depth + dot(n, b.position - a.position), c, corner ? 1u : 0u};
    return resolve_circle_pair(cand, a, b, n, depth, corner);
  };
  auto full = [&](std::uint32_t c) __attribute__((always_inline)) {
    const Candidate& cand = cands[c];
    return collide_circle_pair(cand, bodies[cand.lower], bodies[cand.upper], grown, circle_tests,
                               mixed_tests);
  };
  for (int iteration = 0; iteration < s_.position_iterations; ++iteration) {
    x_.supported.assign(w_.lists.active.size(), 0);
    bool moved = false;
    if (iteration == 0) {
      for (std::uint32_t c = 0; c < candidates; ++c) {
        const Candidate& cand = cands[c];
        if (kPrefetch && c + kPrefetchAhead < candidates) {
          prefetch_pair(bodies, cands[c + kPrefetchAhead]);
        }
        if (!near(bodies[cand.lower], bodies[cand.upper])) continue;
        if (kCapturePass == 0) {
          moved = capture(c, near_count) || moved;
        } else {
          listed[near_count++] = c;
          moved = full(c) || moved;
        }
      }
    } else if (iteration == kCapturePass) {
      std::uint32_t kept = 0;
      for (std::uint32_t k = 0; k < near_count; ++k) {
        if (kPrefetch && k + kPrefetchAhead < near_count) {
          prefetch_pair(bodies, cands[listed[k + kPrefetchAhead]]);
        }
        moved = capture(listed[k], kept) || moved;
      }
      near_count = kept;
    } else {
      relaxed_updates += relaxed_count;
      for (std::uint32_t k = 0; k < relaxed_count; ++k) {
        const auto& pair = relaxed[k];
        const Candidate& cand = cands[pair.candidate];
        if (kPrefetch && k + kPrefetchAhead < relaxed_count) {
          prefetch_pair(bodies, cands[relaxed[k + kPrefetchAhead].candidate]);
        }
        Body& a = bodies[cand.lower];
        Body& b = bodies[cand.upper];
        const double depth = pair.base - dot(pair.normal, b.position - a.position);
        if (depth < -grown) continue;  // apart beyond the grown shapes: no contact
        moved = resolve_circle_pair(cand, a, b, pair.normal, depth, pair.corner != 0) || moved;
      }
      for (std::uint32_t k = 0; k < near_count; ++k) moved = full(listed[k]) || moved;
    }
    if (!moved) break;
  }
  w_.counters.circle_circle_tests += circle_tests;
  w_.counters.circle_box_tests += mixed_tests;
  w_.counters.relaxed_pair_updates += relaxed_updates;
}

// Pushes a and b apart along n (from a toward b) by depth plus slop, split by
// inverse mass, and records the contact for restitution. With shock propagation a
// supported body is immovable for the bodies it carries.
inline bool PositionPass::separate(const Candidate& cand, Body& a, Body& b, Vec2 n, double depth) {
  const double up = dot(n, c_.up);
  if (pins_ && cand.fixed && held_off(cand, b, n)) return false;
  const auto c = static_cast<std::uint32_t>(&cand - w_.candidates.list.data());
  double wa = a.inv_mass;
  double wb = cand.fixed ? 0.0 : b.inv_mass;
  carry(cand.fixed, cand.lower_pos, cand.upper_pos, up, wa, wb);
  const double sum = wa + wb;
  wa /= sum;
  wb /= sum;
  record_contact(c, n);
  // A sleeping body rests on sleeping ones only (update_sleep): one that an awake
  // body presses into from below, however slowly, rests on that body now, and
  // wakes (what rests on it wakes in turn as it moves).
  if (cand.fixed && c_.gravity_on && up > 0.0 && depth > s_.slop && b.is_dynamic()) {
    x_.to_wake.push_back(cand.upper);
  }
  const double push = depth + s_.slop;
  if (depth == 0.0 && !(push > 0.0)) return false;
  a.position -= n * (push * wa);
  b.position += n * (push * wb);
  if (motion_.any_contact_friction && a.contact_friction > 0.0 && b.contact_friction > 0.0) {
    hold_by_static_friction(cand, a, b, n, push, wa, wb);
  }
  // Only pushes against something immovable (a static or sleeping body, or a
  // supported one) may cancel velocity below; a push shared by two free bodies
  // is the velocity solver's to turn into equal and opposite impulses.
  if (wa == 1.0) a.correction -= n * push;
  if (wb == 1.0) b.correction += n * push;
  ++w_.counters.contacts;
  return depth > 0.0;
}

// Whether the push of fixed body b on a pinned body is held off: b is kinematic and
// pushes toward the static body the lower one is pinned against. The static body
// has the last word; the kinematic body overlaps the pinned one instead.
inline bool PositionPass::held_off(const Candidate& cand, const Body& b, Vec2 n) const {
  if (b.motion != Motion::Kinematic) return false;
  const Vec2 wall = x_.position.pin_normal[cand.lower_pos];
  return dot(n, wall) < 0.0;
}

// Static friction in the position passes (as in position-based dynamics, Mueller
// et al., "Detailed Rigid Body Simulation with Extended Position Based Dynamics"):
// a push out along the normal turns the straight-down sink of a body resting on a
// slope into a slide down it, a creep of g*h*h/2*sin(angle) every step that the
// velocity pass cannot undo. When the pair's tangential displacement over the
// sub-step is within the friction cone (at most mu times the push), it is undone:
// a body on a slope no steeper than atan(mu) stays where it was.
inline void PositionPass::hold_by_static_friction(const Candidate& cand, Body& a, Body& b, Vec2 n,
                                                  double push, double wa, double wb) {
  const Vec2 moved_a = a.position - x_.motion.step_start[cand.lower_pos];
  Vec2 moved_b = cand.fixed ? Vec2{} : b.position - x_.motion.step_start[cand.upper_pos];
  // A fixed body moved only if kinematic: by its velocity over the sub-step.
  if (cand.fixed && w_.kinematic_count() != 0 && b.motion == Motion::Kinematic) {
    moved_b = b.velocity * c_.h;
  }
  const Vec2 relative = moved_b - moved_a;
  const Vec2 slide = relative - n * dot(relative, n);
  const double mu = mix_contact_friction(a.contact_friction, b.contact_friction) *
                    load_on(cand.fixed, a, b, dot(n, c_.up));
  if (!(length(slide) <= mu * push)) return;
  if (wa > 0.0 && !may_undo_slide(a, slide)) return;
  if (wb > 0.0 && !may_undo_slide(b, -slide)) return;
  a.position += slide * wa;
  b.position -= slide * wb;
  ++w_.counters.friction_holds;
}

// Whether the hold may move `body` along `undo`. The creep it is for goes the way
// the body is driven (gravity and its own acceleration: downhill, under gravity
// alone), so undoing it never moves a body further that way, and a body driven by
// nothing has no creep to undo. Any other slide is a body escaping a squeeze: the
// pushes of its other contacts lift it out of a pocket, or up a wall, because
// nothing else can move. Undoing that left it at a fixed point deep inside its
// neighbours, and the more friction the deeper: up to 0.096 m in the 16,000-circle
// pile at friction 5 (docs/PHYSICS.md, "Squeezes at high friction").
inline bool PositionPass::may_undo_slide(const Body& body, Vec2 undo) const {
  const Vec2 drive = driving_acceleration(body);
  if (drive.x == 0.0 && drive.y == 0.0) return false;
  return dot(undo, drive) <= 0.0;
}

// gap: how far apart the pair is (at most the margin it was found within).
inline void PositionPass::record_near_miss(const Candidate& cand, Vec2 n, double gap) {
  // A near miss carries weight like a touching contact: the support marks pass
  // through it, or a body resting a slop above its support would not count as
  // supported, and what it carries would push it down into the pile.
  const double up = dot(n, c_.up);
  // A body already supported by a contact found before this one needs no second
  // support straight along gravity from a near miss (a box on two boxes rests on
  // either): half the contacts of a stack for the velocity pass, and the same
  // rest. A slanted one it keeps: a ball in a pocket needs both sides.
  const bool along_gravity = std::fabs(up) >= kAlongGravity;
  if (along_gravity && up > 0.0 && !cand.fixed && x_.supported[cand.upper_pos]) return;
  if (along_gravity && up < 0.0 && x_.supported[cand.lower_pos]) return;
  double wa = 1.0;
  double wb = 1.0;
  carry(cand.fixed, cand.lower_pos, cand.upper_pos, up, wa, wb);
  // It is a contact only while the pair rests on each other, approaching no faster
  // than the rest speed: a faster approach is a collision, which the next step
  // finds as an overlap and bounces.
  Vec2 vb = cand.fixed ? Vec2{} : body(cand.upper).velocity;
  // A kinematic body's velocity is its own, though it is fixed.
  if (cand.fixed && w_.kinematic_count() != 0 && body(cand.upper).motion == Motion::Kinematic) {
    vb = body(cand.upper).velocity;
  }
  if (dot(vb - body(cand.lower).velocity, n) < -c_.rest_speed) return;
  const auto c = static_cast<std::uint32_t>(&cand - w_.candidates.list.data());
  if (x_.marks.contact_of[c] != kNone && !x_.marks.near_miss[c]) return;
  record_contact(c, n);
  x_.marks.near_miss[c] = 1;
  x_.marks.gap[c] = gap;
}

}  // namespace

// The Y phase: boxes on Y (circles wait for the X phase).
void collide_on_y(const StepContext& ctx, WorldImpl& w, const Order& order,
                  const FreeMotion& motion) {
  if (w.kinematic_count() != 0) find_pinned_bodies(ctx, w);
  PositionPass(ctx, w, order, motion).collide_boxes_on<1>();
}

// The X phase: boxes on X, then every pair with a circle.
void collide_on_x(const StepContext& ctx, WorldImpl& w, const Order& order,
                  const FreeMotion& motion) {
  if (w.kinematic_count() != 0) find_pinned_bodies(ctx, w);
  PositionPass pass(ctx, w, order, motion);
  if (motion.any_box) pass.collide_boxes_on<0>();
  if (!motion.any_circle && !(motion.any_box && w.lists.fixed_circles > 0)) return;
  pass.collide_with_circles();
}

}  // namespace phys
