// The order of a sub-step (StepRunner::run), the processing order of the awake
// bodies (lowest first), and WorldImpl::step.
#include <algorithm>
#include <chrono>
#include <utility>
#include <vector>

#include "phase_timer.h"
#include "step_runner.h"

namespace phys {

void StepRunner::run() {
  if (w_.lists_dirty_) w_.rebuild_lists();
  w_.counters.sleeping_bodies_skipped += w_.fixed_sleeping_;
  if (w_.active_.empty()) return;
  {
    PhaseTimer t(s_.profile, w_.profile.integrate);
    order_by_height();
    integrate();
  }
  {
    PhaseTimer t(s_.profile, w_.profile.broadphase);
    find_candidates();
  }
  w_.contact_of_candidate_.assign(w_.candidates_.size(), kNone);
  w_.contact_normal_.resize(w_.candidates_.size());
  w_.contact_near_miss_.resize(w_.candidates_.size());
  w_.contact_gap_.resize(w_.candidates_.size());
  if (any_active_box_) {
    move(1);
    collide_on_y();
    move(0);
  } else {
    move_both_axes();
  }
  collide_on_x();
  if (w_.contact_events_on) {
    PhaseTimer t(s_.profile, w_.profile.narrowphase);
    note_touching_pairs();
  }
  {
    PhaseTimer t(s_.profile, w_.profile.resolve);
    restitution();  // and, with hold_, update_held's work
  }
  {
    PhaseTimer t(s_.profile, w_.profile.sleep);
    hold_in_bounds();
    update_sleep();
  }
}

// Awake bodies are processed from the lowest (along gravity) up, so that a body's
// supports are resolved before it. The order persists between steps and is
// nearly sorted, so insertion sort is about O(N).
inline void StepRunner::order_by_height() {
  auto& order = w_.active_;
  auto& keys = w_.sort_keys_;
  keys.resize(order.size());
  std::size_t jumps = 0;  // neighbours in the order that are not neighbours in slots
  for (std::size_t p = 1; p < order.size(); ++p) {
    jumps += static_cast<std::size_t>(order[p] != order[p - 1] + 1);
  }
  // Far from slot order (a pile that has flowed), the passes over the bodies read
  // them all over memory and prefetch them; in slot order (a stack, a fresh scene)
  // the hardware streams them on its own.
  scattered_ = 4 * jumps > order.size();
  for (std::size_t p = 0; p < order.size(); ++p) {
    if (scattered_) prefetch_ahead(p);
    keys[p] = dot(body(order[p]).position, up_);
  }
  if (w_.joined_ > 0) merge_joined();
  // Heights within the slop are ties, broken by slot: a row of boxes at one height
  // keeps its order although rounding moves them by 1e-16 (and the candidate pairs,
  // grouped by position in this order, can then be reused).
  const double tie = s_.slop;
  const auto before = [tie](double ka, std::uint32_t a, double kb, std::uint32_t b) {
    return ka < kb - tie || (ka <= kb + tie && a < b);
  };
  std::size_t moves = 0;
  const std::size_t budget = 8 * order.size() + 64;
  for (std::size_t p = 1; p < order.size() && moves <= budget; ++p) {
    const double key = keys[p];
    const std::uint32_t slot = order[p];
    std::size_t q = p;
    while (q > 0 && before(key, slot, keys[q - 1], order[q - 1])) {
      keys[q] = keys[q - 1];
      order[q] = order[q - 1];
      --q;
      ++moves;
    }
    keys[q] = key;
    order[q] = slot;
  }
  order_changed_ = order_changed_ || moves > 0;
  if (moves > budget) {  // far from sorted (first step, a shuffle): sort outright
    std::vector<std::pair<double, std::uint32_t>> keyed(order.size());
    for (std::size_t p = 0; p < order.size(); ++p) {
      keyed[p] = {dot(body(order[p]).position, up_), order[p]};
    }
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t p = 0; p < order.size(); ++p) order[p] = keyed[p].second;
  }
}

// The bodies that joined the list at its rebuild (woken or added) wait at its end
// in slot order: sorted by height among themselves and merged into the kept
// bodies' order in one walk, so that the insertion sort has only the usual small
// moves left (from the end, each would walk past most of the list).
inline void StepRunner::merge_joined() {
  auto& order = w_.active_;
  auto& keys = w_.sort_keys_;
  const std::size_t n = order.size();
  const std::size_t kept = n - w_.joined_;
  w_.joined_ = 0;
  auto& keyed = w_.keyed_order_;
  keyed.resize(n);
  for (std::size_t p = 0; p < n; ++p) keyed[p] = {keys[p], order[p]};
  std::sort(keyed.begin() + static_cast<std::ptrdiff_t>(kept), keyed.end());
  std::size_t i = 0;
  std::size_t j = kept;
  for (std::size_t p = 0; p < n; ++p) {
    const bool take_kept = j == n || (i < kept && !(keyed[j] < keyed[i]));
    const auto& next = take_kept ? keyed[i++] : keyed[j++];
    keys[p] = next.first;
    order[p] = next.second;
  }
  order_changed_ = true;
}

void WorldImpl::step(double dt) {
  const auto start = std::chrono::steady_clock::now();
  profile = {};
  const double h = dt / settings.substeps;
  if (contact_events_on) contact_tracker.begin_step();
  for (int i = 0; i < settings.substeps; ++i) {
    StepRunner(*this, h).run();
    ++counters.substeps;
  }
  ++steps;
  ++counters.steps;
  if (contact_events_on) counters.contact_events += contact_tracker.finish(steps, bodies);
  if (settings.profile) {
    profile.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
}

}  // namespace phys
