// The processing order of the awake bodies: lowest (along gravity) first, so that
// a body's supports are resolved before it. Reads the bodies' positions; writes
// the order (BodyLists::active, and `joined` back to 0) and scratch.order.
#include <algorithm>
#include <utility>
#include <vector>

#include "step_phases.h"
#include "step_shared.h"

namespace phys {

namespace {

class OrderPass : StepPhase {
 public:
  OrderPass(const StepContext& ctx, WorldImpl& world) : StepPhase(ctx, world) {}
  Order run();

 private:
  void merge_joined();
};

// Awake bodies are processed from the lowest (along gravity) up, so that a body's
// supports are resolved before it. The order persists between steps and is
// nearly sorted, so insertion sort is about O(N).
inline Order OrderPass::run() {
  auto& order = w_.lists.active;
  auto& keys = x_.order.keys;
  keys.resize(order.size());
  std::size_t jumps = 0;  // neighbours in the order that are not neighbours in slots
  for (std::size_t p = 1; p < order.size(); ++p) {
    jumps += static_cast<std::size_t>(order[p] != order[p - 1] + 1);
  }
  // Far from slot order (a pile that has flowed), the passes over the bodies read
  // them all over memory and prefetch them; in slot order (a stack, a fresh scene)
  // the hardware streams them on its own.
  const bool scattered = 4 * jumps > order.size();
  for (std::size_t p = 0; p < order.size(); ++p) {
    if (scattered) prefetch_ahead(p);
    keys[p] = dot(body(order[p]).position, c_.up);
  }
  const bool merged = w_.lists.joined > 0;
  if (merged) merge_joined();
  // While the candidate pairs hold, the sort carries each body's old position along,
  // so that the pairs survive a reordering (step_integrate.cpp renumbers them).
  // It starts at the first move: a stack whose order holds pays nothing for it.
  const bool track = w_.candidates.valid && !merged;
  auto& from = x_.order.from;
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
    }
    if (q == p) continue;
    keys[q] = key;
    order[q] = slot;
    if (track) {
      if (moves == 0) {
        from.resize(order.size());
        for (std::size_t k = 0; k < order.size(); ++k) from[k] = static_cast<std::uint32_t>(k);
      }
      const std::uint32_t was = from[p];
      for (std::size_t k = p; k > q; --k) from[k] = from[k - 1];
      from[q] = was;
    }
    moves += p - q;
  }
  if (moves > budget) {  // far from sorted (first step, a shuffle): sort outright
    std::vector<std::pair<double, std::uint32_t>> keyed(order.size());
    for (std::size_t p = 0; p < order.size(); ++p) {
      keyed[p] = {dot(body(order[p]).position, c_.up), order[p]};
    }
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t p = 0; p < order.size(); ++p) order[p] = keyed[p].second;
  }
  const bool changed = merged || moves > 0;
  return {changed, changed && track && moves <= budget, scattered};
}

// The bodies that joined the list at its rebuild (woken or added) wait at its end
// in slot order: sorted by height among themselves and merged into the kept
// bodies' order in one walk, so that the insertion sort has only the usual small
// moves left (from the end, each would walk past most of the list).
inline void OrderPass::merge_joined() {
  auto& order = w_.lists.active;
  auto& keys = x_.order.keys;
  const std::size_t n = order.size();
  const std::size_t kept = n - w_.lists.joined;
  w_.lists.joined = 0;
  auto& keyed = x_.order.keyed;
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
}

}  // namespace

Order order_by_height(const StepContext& ctx, WorldImpl& w) { return OrderPass(ctx, w).run(); }

}  // namespace phys
