// What this sub-step's contacts leave for the next one, after the velocity solver:
// the warm-start impulses of each awake body's contacts, and (with shock
// propagation and contact friction) each body's load factor.
// Reads: the velocity solver's contact records, the processing order, the bodies.
// Writes: the warm-start pool (WorldImpl::warm_pool, warm_first, warm_count), the
// bodies' loads, scratch.velocity's support_impulse and carried_impulse.
#include <algorithm>
#include <cstdint>
#include <span>

#include "step_phases.h"
#include "step_shared.h"

namespace phys {

namespace {

class LoadPass : StepPhase {
 public:
  LoadPass(const StepContext& ctx, WorldImpl& world, bool scattered)
      : StepPhase(ctx, world), scattered_(scattered) {}
  // Shock propagation makes a supported body immovable for what rests on it, so its
  // own contacts below push up only its own weight: the weight of the pile above it
  // never reaches them, and friction, bounded by the push, holds it as if nothing
  // rested on it. Bodies deep in a pile are then pushed aside by their neighbours
  // and the pile creeps down. So the load is put back, for friction only: from the
  // top of the pile down, each body's supports carry its own push plus what rests
  // on it, shared among them as they share its own push, and its load factor
  // (Body::load) is that total over its own. Contacts are grouped by their lower
  // body's position in the processing order (bottom up), so one walk from the end
  // meets every body's load from above before its own supports.
  void run(std::span<const ContactRecord> contacts) {
    const std::size_t n = w_.lists.active.size();
    auto& own = x_.velocity.support_impulse;
    auto& carried = x_.velocity.carried_impulse;
    own.assign(n, 0.0);
    carried.assign(n, 0.0);
    for (const ContactRecord& k : contacts) {
      if (k.up < -kSupportCosine) own[k.lower_pos] -= k.impulse * k.up;
      if (k.up > kSupportCosine && !k.fixed) own[k.upper_pos] += k.impulse * k.up;
    }
    // A body whose supports pushed less than its weight (landing, or held by the
    // position passes) shares what it carries as if they had pushed its weight.
    const double weight = length(s_.gravity) * c_.h;  // a body's own push, per unit mass
    const auto factor = [&](std::uint32_t p) {
      const double resting = std::max(own[p], body(w_.lists.active[p]).mass * weight);
      return std::max(1.0, (own[p] + carried[p]) / resting);
    };
    for (std::size_t i = contacts.size(); i-- > 0;) {
      const ContactRecord& k = contacts[i];
      if (k.fixed) continue;  // a static or sleeping body passes nothing on
      if (k.up > kSupportCosine) {
        carried[k.lower_pos] += k.impulse * k.up * factor(k.upper_pos);
      } else if (k.up < -kSupportCosine) {
        carried[k.upper_pos] -= k.impulse * k.up * factor(k.lower_pos);
      }
    }
    for (std::uint32_t p = 0; p < n; ++p) {
      if (scattered_) prefetch_ahead(p);
      body(w_.lists.active[p]).load = factor(p);
    }
  }

 private:
  const bool scattered_;  // the processing order is far from slot order
};

}  // namespace

void update_loads(const StepContext& ctx, WorldImpl& w, const Order& order,
                  std::span<const ContactRecord> contacts) {
  LoadPass(ctx, w, order.scattered).run(contacts);
}

// Each awake body keeps the impulses of the contacts it was the lower body of.
void remember_impulses(WorldImpl& w, std::span<const ContactRecord> contacts) {
  // Contacts come grouped by the lower body's position: one walk rewrites the
  // pool in processing order.
  auto& pool = w.warm_pool;
  pool.clear();
  std::size_t i = 0;
  for (std::uint32_t p = 0; p < w.lists.active.size(); ++p) {
    const std::uint32_t slot = w.lists.active[p];
    const auto first = static_cast<std::uint32_t>(pool.size());
    std::uint8_t count = 0;
    for (; i < contacts.size() && contacts[i].lower_pos == p; ++i) {
      const ContactRecord& k = contacts[i];
      if (k.impulse <= 0.0) continue;
      if (count < kWarmSlots) {
        pool.push_back({k.upper, k.upper_generation, k.impulse, k.tangent_impulse});
        ++count;
      } else {
        ++w.counters.warm_start_overflows;
      }
    }
    w.warm_first[slot] = first;
    w.warm_count[slot] = count;
  }
}

}  // namespace phys
