// The world's bounds, and sleep: bodies still for sleep_time fall asleep as an
// island, from the bottom up, or as a group held by what sleeps.
// Reads: the bodies, the candidates (islands), the velocity solver's contact
// records (what rests on what), scratch.to_wake.
// Writes: the bodies' positions and velocities (bounds), their stillness and
// sleep; wakes what was hit; scratch.sleep.
#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "step_phases.h"
#include "step_shared.h"

namespace phys {

namespace {

// Where a Body's cold line begins (its third cache line: still_time and after).
constexpr std::size_t kColdLineOffset = 2 * 64;
static_assert(offsetof(Body, still_time) >= kColdLineOffset &&
                  offsetof(Body, still_anchor) + sizeof(Vec2) <= 3 * 64,
              "update_sleep prefetches the line of still_time and still_anchor");

// sleep_held_groups' states of a still body.
constexpr std::uint8_t kCandidate = 1;
constexpr std::uint8_t kBlocked = 2;
constexpr std::uint8_t kGrounded = 3;

class SleepPass : StepPhase {
 public:
  SleepPass(const StepContext& ctx, WorldImpl& world, const Order& order,
            std::span<const ContactRecord> contacts)
      : StepPhase(ctx, world), scattered_(order.scattered), contacts_(contacts) {}
  void run();

 private:
  // prefetch_ahead, for a loop that reads a body's cold line too (still_time and
  // after).
  void prefetch_ahead_with_cold_line(std::size_t p) const {
    if (p + kPrefetchAhead < w_.lists.active.size()) {
      const Body* b = &w_.bodies[w_.lists.active[p + kPrefetchAhead]];
      __builtin_prefetch(b);
      __builtin_prefetch(reinterpret_cast<const char*>(b) + kColdLineOffset);
    }
  }
  void sleep_from_the_bottom(std::vector<std::uint8_t>& asleep);
  void sleep_held_groups(std::span<const ContactRecord> contacts,
                         std::vector<std::uint8_t>& asleep);

  const bool scattered_;                           // the processing order is far from slot order
  const std::span<const ContactRecord> contacts_;  // the velocity solver's records
};

}  // namespace

// A world with bounds keeps every awake body inside them: one beyond an edge is put
// back on it and keeps no velocity out of it.
void hold_in_bounds(const StepContext& ctx, WorldImpl& w) {
  const WorldSettings& s = ctx.settings;
  if (!s.has_bounds) return;
  for (std::uint32_t slot : w.lists.active) {
    Body& b = w.bodies[slot];
    bool clamped = false;
    for (int axis = 0; axis < 2; ++axis) {
      const double lo = component(s.bounds.min, axis) + component(b.half, axis);
      const double hi = component(s.bounds.max, axis) - component(b.half, axis);
      double& x = component(b.position, axis);
      double& v = component(b.velocity, axis);
      if (x < lo) {
        x = std::min(lo, hi);
        v = std::max(v, 0.0);
        clamped = true;
      } else if (x > hi) {
        x = std::max(hi, lo);
        v = std::min(v, 0.0);
        clamped = true;
      }
    }
    if (clamped) ++w.counters.bounds_clamps;
  }
}

// A body that has been still for sleep_time is ready to sleep. Bodies near each
// other form an island (union-find over this sub-step's candidate pairs, static
// and sleeping bodies not linking), and an island sleeps when all of it is ready,
// or from the bottom up as far as it is (sleep_from_the_bottom).
void SleepPass::run() {
  for (std::uint32_t slot : x_.to_wake) w_.wake(slot);
  x_.to_wake.clear();
  if (!s_.sleeping) return;
  const std::size_t n = w_.lists.active.size();
  bool any_ready = false;
  // "Still" is judged over the window, not by the speed of one step: a body of a
  // pile jitters by rounding-sized pushes at any instant, but a body at rest stays
  // within sleep_speed * sleep_time of where the window began.
  const double radius = s_.sleep_speed * s_.sleep_time;
  // Whether each body is ready is kept by position: the walks below read it there
  // instead of from the body's cold cache line, all over memory.
  auto& ready = x_.sleep.still_ready;
  ready.resize(n);
  for (std::uint32_t p = 0; p < n; ++p) {
    if (scattered_) prefetch_ahead_with_cold_line(p);
    Body& b = body(w_.lists.active[p]);
    if (length(b.position - b.still_anchor) > radius) {
      b.still_anchor = b.position;
      b.still_time = 0.0;
    } else {
      b.still_time += c_.h;
    }
    ready[p] = static_cast<std::uint8_t>(b.still_time >= s_.sleep_time);
    any_ready = any_ready || ready[p] != 0;
  }
  if (!any_ready) return;

  auto& parent = x_.sleep.island_parent;
  parent.resize(n);
  for (std::uint32_t p = 0; p < n; ++p) parent[p] = p;
  const auto root = [&parent](std::uint32_t p) {
    while (parent[p] != p) p = parent[p] = parent[parent[p]];
    return p;
  };
  // Islands link through candidate pairs, not only touching ones: neighbours a
  // slop apart in a pile are one island, so no part of a pile sleeps alone.
  for (const Candidate& cand : w_.candidates.list) {
    if (cand.fixed) continue;
    const std::uint32_t a = root(cand.lower_pos);
    const std::uint32_t b = root(cand.upper_pos);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  auto& island_ready = x_.sleep.island_ready;
  island_ready.assign(n, 1);
  for (std::uint32_t p = 0; p < n; ++p) {
    if (!ready[p]) island_ready[root(p)] = 0;
  }
  auto& asleep = x_.sleep.goes_to_sleep;
  asleep.resize(n);
  for (std::uint32_t p = 0; p < n; ++p) asleep[p] = island_ready[root(p)];
  if (c_.gravity_on) sleep_from_the_bottom(asleep);  // no "below" without gravity
  for (std::uint32_t p = 0; p < n; ++p) {
    if (!asleep[p]) continue;
    Body& b = body(w_.lists.active[p]);
    b.awake = false;
    b.velocity = {};
    b.held = {};
    b.load = 1.0;
    w_.fell_asleep(w_.lists.active[p]);
  }
}

// An island sleeps as a whole when all of it is ready; in one that is not, a
// ready body still sleeps when it rests only on what is asleep or static: it has
// a contact below it (one whose normal has any component along "up", a steep
// one of an arch too), and every body below it that it touches is asleep. Bodies
// come from the lowest up, so a still pile falls asleep from the floor up to
// where something still moves, in one pass; what rests on a moving body stays
// awake. A sleeping body is as immovable for what it carries as shock
// propagation already makes a supported one, so the bodies above see no change;
// without this, one avalanche anywhere in a pile of 16,000 kept all of it awake.
inline void SleepPass::sleep_from_the_bottom(std::vector<std::uint8_t>& asleep) {
  const std::span<const ContactRecord> contacts = contacts_;
  const std::size_t n = w_.lists.active.size();
  auto& first = x_.sleep.first_support;
  auto& supporters = x_.sleep.supporters;
  auto& cursor = x_.sleep.support_cursor;
  // Each contact with a vertical component: the awake body on top (kNone when
  // that is the fixed one, which needs no support) and the one under it.
  struct Link {
    std::uint32_t carried;
    std::uint32_t supporter;  // kNone when static or sleeping
  };
  const auto link_of = [](const ContactRecord& k) {
    if (k.up > 0.0) return Link{k.fixed ? kNone : k.upper_pos, k.lower_pos};
    if (k.up < 0.0) return Link{k.lower_pos, k.fixed ? kNone : k.upper_pos};
    return Link{kNone, kNone};
  };
  first.assign(n + 1, 0);
  for (const ContactRecord& k : contacts) {
    const Link link = link_of(k);
    if (link.carried != kNone) ++first[link.carried + 1];
  }
  for (std::size_t p = 0; p < n; ++p) first[p + 1] += first[p];
  supporters.resize(first[n]);
  cursor.assign(first.begin(), first.end() - 1);
  for (const ContactRecord& k : contacts) {
    const Link link = link_of(k);
    if (link.carried != kNone) supporters[cursor[link.carried]++] = link.supporter;
  }
  for (std::uint32_t p = 0; p < n; ++p) {
    if (asleep[p] || first[p] == first[p + 1]) continue;
    if (!x_.sleep.still_ready[p]) continue;
    // A supporter later in the order (level with p, within the slop) is not judged
    // yet: p waits for the next sub-step.
    const auto on_sleeper = [&](std::uint32_t q) { return q == kNone || asleep[q] != 0; };
    if (std::all_of(supporters.begin() + first[p], supporters.begin() + first[p + 1], on_sleeper)) {
      asleep[p] = 1;
    }
  }
  sleep_held_groups(contacts, asleep);
}

// The pass above never sleeps a body with no contact below it: one wedged between
// its neighbours and held up by their friction (a keystone), still for seconds.
// Nor, then, the neighbours resting on it, nor anything above them: in a pile of
// 16,000 with friction, 7,000 still bodies stayed awake for ever over a handful
// of keystones. So still bodies left awake sleep together, as a group, when
// whatever holds any of them is asleep, static or in the group: a body's holders
// are the bodies below it that it touches, or, with none below, every body it
// touches. A still body held by a moving one is blocked, and so is every body
// it holds, and so on (a walk over the holders, cycles and all). Of the rest, a
// body sleeps if its holders lead down to a static or sleeping body (grounded):
// a group held by nothing asleep is not at rest on anything.
inline void SleepPass::sleep_held_groups(std::span<const ContactRecord> contacts,
                                         std::vector<std::uint8_t>& asleep) {
  const std::size_t n = w_.lists.active.size();
  auto& state = x_.sleep.held_state;  // per position: kCandidate, kBlocked, kGrounded, or 0
  state.assign(n, 0);
  bool any = false;
  for (std::uint32_t p = 0; p < n; ++p) {
    if (!asleep[p] && x_.sleep.still_ready[p]) {
      state[p] = kCandidate;
      any = true;
    }
  }
  if (!any) return;
  const auto& first = x_.sleep.first_support;
  const auto has_support = [&first](std::uint32_t p) { return first[p] != first[p + 1]; };
  // (held, holder) pairs, holder kNone when static or sleeping.
  auto& holds = x_.sleep.holds;
  holds.clear();
  const auto add = [&](std::uint32_t held, std::uint32_t holder) {
    if (state[held] != kCandidate) return;
    holds.push_back({held, holder != kNone && asleep[holder] ? kNone : holder});
  };
  for (const ContactRecord& k : contacts) {
    const std::uint32_t lower = k.lower_pos;
    const std::uint32_t upper = k.fixed ? kNone : k.upper_pos;
    // The support links of sleep_from_the_bottom, and every contact of a body
    // with none.
    if (k.up < 0.0 || !has_support(lower)) add(lower, upper);
    if (upper != kNone && (k.up > 0.0 || !has_support(upper))) add(upper, lower);
  }
  // Who each awake body holds, for the walks (CSR by holder).
  auto& start = x_.sleep.held_start;
  auto& held_by = x_.sleep.held_list;
  start.assign(n + 1, 0);
  for (const auto& h : holds) {
    if (h.second != kNone) ++start[h.second + 1];
  }
  for (std::size_t p = 0; p < n; ++p) start[p + 1] += start[p];
  held_by.resize(start[n]);
  auto& cursor = x_.sleep.support_cursor;
  cursor.assign(start.begin(), start.end() - 1);
  for (const auto& h : holds) {
    if (h.second != kNone) held_by[cursor[h.second]++] = h.first;
  }
  // Blocked: held by a moving body, or by a blocked one.
  auto& work = x_.sleep.held_work;
  work.clear();
  for (const auto& h : holds) {
    if (h.second != kNone && state[h.second] == 0 && state[h.first] == kCandidate) {
      state[h.first] = kBlocked;
      work.push_back(h.first);
    }
  }
  const auto spread = [&](std::uint8_t from, std::uint8_t to) {
    while (!work.empty()) {
      const std::uint32_t q = work.back();
      work.pop_back();
      for (std::uint32_t i = start[q]; i < start[q + 1]; ++i) {
        const std::uint32_t p = held_by[i];
        if (state[p] == from) {
          state[p] = to;
          work.push_back(p);
        }
      }
    }
  };
  spread(kCandidate, kBlocked);
  // Grounded: held by a static or sleeping body, or by a grounded one.
  for (const auto& h : holds) {
    if (h.second == kNone && state[h.first] == kCandidate) {
      state[h.first] = kGrounded;
      work.push_back(h.first);
    }
  }
  spread(kCandidate, kGrounded);
  for (std::uint32_t p = 0; p < n; ++p) {
    if (state[p] == kGrounded) asleep[p] = 1;
  }
}

void update_sleep(const StepContext& ctx, WorldImpl& w, const Order& order,
                  std::span<const ContactRecord> contacts) {
  SleepPass(ctx, w, order, contacts).run();
}

}  // namespace phys
