#pragma once
// The position passes' worker, shared by the box passes (step_position.cpp) and the
// circle passes (step_position_circles.cpp): the Gauss-Seidel loop over the
// candidate pairs and what a pair that touches or nearly touches does (pushed
// apart, held by static friction, recorded as a contact or a near miss). Defined
// here, inline: each is the body of a pair loop, and the compiler inlines them there.
//
// In an unnamed namespace on purpose, though this is a header: each of the two files
// gets its own copy with internal linkage, which the compiler inlines into the pair
// loops as it did when they were one file. With external linkage the rain-4000's
// position passes ran 12% slower (physics-bench, thread CPU time per step).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "step_phases.h"
#include "step_shared.h"

namespace phys {

// The pairs with a circle (step_position_circles.cpp), after the boxes of the X phase.
void collide_circle_pairs(const StepContext& ctx, WorldImpl& w, const Order& order,
                          const FreeMotion& motion);

namespace {  // see above: internal linkage in each file that includes this

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
  void collide_boxes_on();      // step_position.cpp
  void collide_with_circles();  // step_position_circles.cpp (collide_circle_pairs)

 private:
  template <bool kPrefetch>
  void relaxed_circle_passes();
  bool resolve_circle_pair(const Candidate& cand, Body& a, Body& b, Vec2 n, double depth,
                           bool corner);
  bool collide_circle_pair(const Candidate& cand, Body& a, Body& b, double grown,
                           std::uint64_t& circle_tests, std::uint64_t& mixed_tests);
  double near_gap(const Body& a, const Body& b) const;
  bool near(const Body& a, const Body& b) const;
  template <typename Pass>
  void iterate(Pass& pass);
  template <bool kPrefetch, typename Visit>
  bool visit_near_pairs(const Candidate* cands, const Body* bodies, std::uint32_t candidates,
                        Visit& visit) const;
  template <bool kPrefetch, typename Visit>
  static bool visit_listed(const Candidate* cands, const Body* bodies, const std::uint32_t* listed,
                           std::uint32_t count, Visit& visit);
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

// Up to position_iterations passes, `pass(iteration)` each, with the support marks
// cleared before each, until a pass moves nothing (pass returns false).
template <typename Pass>
__attribute__((always_inline)) inline void PositionPass::iterate(Pass& pass) {
  for (int iteration = 0; iteration < s_.position_iterations; ++iteration) {
    x_.supported.assign(w_.lists.active.size(), 0);
    if (!pass(iteration)) break;
  }
}

// The first pass's loop: every candidate pair near enough to matter, in candidate
// order, with visit(c, cand) for each; true when a visit moved a body.
template <bool kPrefetch, typename Visit>
__attribute__((always_inline)) inline bool PositionPass::visit_near_pairs(const Candidate* cands,
                                                                          const Body* bodies,
                                                                          std::uint32_t candidates,
                                                                          Visit& visit) const {
  bool moved = false;
  for (std::uint32_t c = 0; c < candidates; ++c) {
    const Candidate& cand = cands[c];
    if (kPrefetch && c + kPrefetchAhead < candidates) {
      prefetch_pair(bodies, cands[c + kPrefetchAhead]);
    }
    if (!near(bodies[cand.lower], bodies[cand.upper])) continue;
    moved = visit(c, cand) || moved;
  }
  return moved;
}

// A later pass's loop: the candidates `listed`, in order, with visit(c) for each;
// true when a visit moved a body.
template <bool kPrefetch, typename Visit>
__attribute__((always_inline)) inline bool PositionPass::visit_listed(const Candidate* cands,
                                                                      const Body* bodies,
                                                                      const std::uint32_t* listed,
                                                                      std::uint32_t count,
                                                                      Visit& visit) {
  bool moved = false;
  for (std::uint32_t k = 0; k < count; ++k) {
    if (kPrefetch && k + kPrefetchAhead < count) {
      prefetch_pair(bodies, cands[listed[k + kPrefetchAhead]]);
    }
    moved = visit(listed[k]) || moved;
  }
  return moved;
}

// Gauss-Seidel passes over the candidate pairs: the first pass visits all of them
// and keeps the pairs near enough to matter; later passes visit only those.
// The passes come in two builds: with prefetching for bodies scattered in
// memory, and without it, so that a stack's loop carries no trace of it. Measured
// against one instance (bench/compare-core.sh, thread CPU time per step): never
// prefetching, rain-16000 ran 1.28x (sleep on) / 1.41x (off); always, the awake
// pyramid-5050 ran 1.022x, 3% over the run-to-run noise's mean. The pair
// tests given to it (the lambdas of the box and circle passes) are forced inline:
// each is the loop's body, and the compiler's own budget, spent on the passes
// inlined into their phase, left a call per pair.
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
  // The pointers go into the lambdas by value, so that they stay plain pointers too.
  auto first = [&resolve, &near_count, listed, bodies ](std::uint32_t c, const Candidate& cand)
      __attribute__((always_inline)) {
    listed[near_count++] = c;
    return resolve(cand, bodies[cand.lower], bodies[cand.upper]);
  };
  auto again = [&resolve, cands, bodies ](std::uint32_t c) __attribute__((always_inline)) {
    const Candidate& cand = cands[c];
    return resolve(cand, bodies[cand.lower], bodies[cand.upper]);
  };
  auto pass = [&](int iteration) __attribute__((always_inline)) {
    if (iteration == 0) return visit_near_pairs<kPrefetch>(cands, bodies, candidates, first);
    return visit_listed<kPrefetch>(cands, bodies, listed, near_count, again);
  };
  iterate(pass);
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
}  // namespace phys
