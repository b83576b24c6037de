// The position passes' pairs with a circle, resolved along their normal (a
// circle's normal needs no axis split), with the relaxed passes
// (WorldSettings::relaxed_position_passes) that find a touching pair's penetration
// again from its normal alone. The pair loop and the contact rules are in
// step_position_pass.h.
#include <cstdint>

#include "step_position_pass.h"

namespace phys {
namespace {

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
// Forced inline, as the compiler chose when the position passes were one file.
__attribute__((always_inline)) inline bool PositionPass::resolve_circle_pair(const Candidate& cand,
                                                                             Body& a, Body& b,
                                                                             Vec2 n, double depth,
                                                                             bool corner) {
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
  // The passes after the capture: each touching pair's penetration from its moves
  // along its kept normal, then the near pairs that did not touch by the narrowphase.
  auto relaxed_pass = [&]() __attribute__((always_inline)) {
    bool moved = false;
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
    return visit_listed<false>(cands, bodies, listed, near_count, full) || moved;
  };
  auto first = [&](std::uint32_t c, const Candidate&) __attribute__((always_inline)) {
    if (kCapturePass == 0) return capture(c, near_count);
    listed[near_count++] = c;
    return full(c);
  };
  auto pass = [&](int iteration) __attribute__((always_inline)) {
    if (iteration == 0) return visit_near_pairs<kPrefetch>(cands, bodies, candidates, first);
    if (iteration != kCapturePass) return relaxed_pass();
    std::uint32_t kept = 0;
    auto keep = [&](std::uint32_t c) __attribute__((always_inline)) { return capture(c, kept); };
    const bool moved = visit_listed<kPrefetch>(cands, bodies, listed, near_count, keep);
    near_count = kept;
    return moved;
  };
  iterate(pass);
  w_.counters.circle_circle_tests += circle_tests;
  w_.counters.circle_box_tests += mixed_tests;
  w_.counters.relaxed_pair_updates += relaxed_updates;
}

}  // namespace

// A pass of its own for the circles: it holds nothing the box pass before it changed
// (the pinned bodies are found before either).
void collide_circle_pairs(const StepContext& ctx, WorldImpl& w, const Order& order,
                          const FreeMotion& motion) {
  PositionPass(ctx, w, order, motion).collide_with_circles();
}

}  // namespace phys
