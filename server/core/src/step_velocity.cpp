// The velocity phase: sequential impulses over the contacts the position passes
// found (restitution, contact friction, shock propagation, warm start), and what
// the contacts held of each body's acceleration.
#include <algorithm>
#include <cmath>

#include "branchless.h"
#include "step_runner.h"

namespace phys {

// The velocity component along each contact's normal is reflected and scaled by
// the restitution (zeroed below the rest speed), impulses split by inverse mass.
void StepRunner::restitution() {
  // Records are written in place: the array only grows (no clearing, no growth
  // check per contact), contact_count_ says how many are this sub-step's.
  if (w_.contacts_.size() < w_.candidates_.size()) w_.contacts_.resize(w_.candidates_.size());
  contact_count_ = 0;
  // Without friction, the iterations run two contacts at a time, with the same
  // results (ContactLanes). Shock propagation's weights for them are found as the
  // contacts are gathered, in the same order.
  lanes_ = kHaveContactLanes && !any_contact_friction_;
  if (lanes_) {
    if (w_.contact_weights_.size() < w_.candidates_.size()) {
      w_.contact_weights_.resize(w_.candidates_.size());
    }
    w_.supported_.assign(w_.active_.size(), 0);
  }
  // Gather the marked candidates in candidate order, with what the iterations read.
  // Candidates come grouped by their lower body's position p, and a body is never
  // read again once its group is done (later groups hold only higher bodies), so
  // its velocity is cancelled into its corrections right there, while it is in
  // cache. With no contact at all every correction is zero and that changes nothing.
  const double per_second = 1.0 / h_;
  const auto active = static_cast<std::uint32_t>(w_.active_.size());
  const auto candidate_count = static_cast<std::uint32_t>(w_.candidates_.size());
  // The iterations read and write only awake bodies' velocities (a fixed body's
  // counts as zero): they work on a dense copy by position, written back at the end.
  // One velocity more, always zero: what a fixed body's lane reads (ContactLanes).
  auto& velocity = w_.solver_velocity_;
  velocity.resize(active + 1);
  velocity[active] = {};
  if (hold_) {  // what the contacts will do along "up" is measured from here
    w_.velocity_before_contacts_.resize(active);
    w_.in_contact_.assign(active, 0);
  }
  for (std::uint32_t p = 0; p < active; ++p) {
    if (scattered_) prefetch_ahead(p);
    for (std::uint32_t c = w_.first_candidate_[p]; c < w_.first_candidate_[p + 1]; ++c) {
      // The upper bodies are anywhere in memory, as the lower ones are.
      if (scattered_ && c + kPrefetchAhead < candidate_count) {
        __builtin_prefetch(&w_.bodies[w_.candidates_[c + kPrefetchAhead].upper]);
      }
      if (w_.contact_of_candidate_[c] != kNone) gather_contact(c);
    }
    // Cancelled in a register and stored whole: reading back a velocity just
    // stored one half at a time stalls the load.
    Body& b = body(w_.active_[p]);
    if (hold_) w_.velocity_before_contacts_[p] = b.velocity;
    const Vec2 v = cancelled_velocity(b.velocity, b.correction, per_second);
    b.velocity = v;
    velocity[p] = v;
  }
  if (contact_count_ == 0) {  // no contact holds anything
    if (hold_) update_held();
    return;
  }
  ++w_.counters.restitution_passes;
  const std::span<ContactRecord> contacts(w_.contacts_.data(), contact_count_);
  Vec2* const solver = velocity.data();
  const bool shock = shock_;
  if (lanes_) {
    const std::span<const ContactWeights> weights(w_.contact_weights_.data(), contact_count_);
    w_.contact_lanes_.pack(contacts, weights, active);
  }
  for (int iteration = 0; iteration < s_.velocity_iterations; ++iteration) {
    bool changed = false;
    if (lanes_) {
      changed = w_.contact_lanes_.iterate(solver, iteration == 0);
    } else {
      w_.supported_.assign(w_.active_.size(), 0);
      std::uint8_t* const supported = w_.supported_.data();
      if (any_contact_friction_) {
        solve_contacts<true>(contacts, solver, supported, shock, iteration == 0, changed);
      } else {
        solve_contacts<false>(contacts, solver, supported, shock, iteration == 0, changed);
      }
    }
    if (!changed && iteration > 0) break;
  }
  if (lanes_) w_.contact_lanes_.unpack(contacts);
  // The velocities go back to the bodies; what the contacts held of each one's
  // acceleration is found in the same walk (update_held's, while the body is in cache).
  for (std::uint32_t p = 0; p < active; ++p) {
    if (scattered_) prefetch_ahead(p);
    Body& b = body(w_.active_[p]);
    b.velocity = velocity[p];
    if (hold_) update_held(p, b);
  }
  if (s_.warm_starting) remember_impulses();
  if (shock_ && any_contact_friction_) update_loads(contacts);
}

// One iteration over the contacts. Built apart for scenes with contact friction
// and without (kFriction): without it, no contact has friction to apply.
template <bool kFriction>
inline void StepRunner::solve_contacts(std::span<ContactRecord> contacts, Vec2* solver,
                                       std::uint8_t* supported, bool shock, bool first_iteration,
                                       bool& changed) {
  for (ContactRecord& k : contacts) {
    if (k.fixed) {
      solve_contact<true, kFriction>(k, solver, supported, shock, first_iteration, changed);
    } else {
      solve_contact<false, kFriction>(k, solver, supported, shock, first_iteration, changed);
    }
  }
}

// One contact in one iteration of the restitution phase, built apart for contacts
// with a fixed body (no velocity of its own) and between two awake bodies, so
// that neither carries the other's tests.
template <bool kFixed, bool kFriction>
inline void StepRunner::solve_contact(ContactRecord& k, Vec2* solver, std::uint8_t* supported,
                                      bool shock, bool first_iteration, bool& changed) {
  Vec2 fixed_velocity{};  // what vb names for a fixed body; never read
  Vec2& va = solver[k.lower_pos];
  Vec2& vb = kFixed ? fixed_velocity : solver[k.upper_pos];
  const Vec2 n = k.normal;
  double wa = k.inv_mass_lower;
  double wb = k.inv_mass_upper;
  carry(supported, shock, kFixed, k.lower_pos, k.upper_pos, k.up, wa, wb);
  // The pair's effective mass, once for the normal and the friction impulse.
  const double mass = 1.0 / (wa + wb);
  double closing = dot((kFixed ? Vec2{} : vb) - va, n);
  // An immovable supporter can stop the bodies it carries but never lift them:
  // its own motion away from them counts as zero. Otherwise a supported body
  // moving up hands its velocity to every body above it, all the way up a pile.
  if (wa == 0.0 && !kFixed) closing += std::max(dot(va, n), 0.0);
  if (wb == 0.0 && !kFixed) closing -= std::min(dot(vb, n), 0.0);
  if (wa + wb <= 0.0) return;
  // Sequential impulses: the impulse accumulated on a contact may shrink again
  // but never pull (stay >= 0), so iterations converge to a velocity that
  // neither approaches nor separates from resting contacts.
  double& total = k.impulse;
  if (first_iteration && k.warm > 0.0) {
    // Warm start: begin from last step's impulse on this pair, so resting
    // contacts converge over steps instead of within one.
    total = k.warm;
    va -= n * (total * wa);
    if (!kFixed) vb += n * (total * wb);
    changed = true;
    if (k.mu > 0.0) {
      // Friction warm-starts too, within the cone of the warm normal impulse
      // (Box2D's warm start of the tangent impulse): a pile holds its
      // sideways loads through chains of friction that a few iterations from
      // zero would not rebuild every step.
      const Vec2 t{-n.y, n.x};
      const double limit = k.mu * total;
      k.tangent_impulse = std::clamp(k.warm_tangent, -limit, limit);
      va -= t * (k.tangent_impulse * wa);
      if (!kFixed) vb += t * (k.tangent_impulse * wb);
      apply_contact_friction<kFixed>(k, va, vb, wa, wb, mass);
    }
    return;
  }
  // Without friction, no branch on whether the impulse clamps or changes: in a
  // flowing pile either is a coin toss per contact (a zero impulse changes no
  // velocity's value), and resolve is 21% faster so. With friction, where
  // contacts hold and their impulses settle, the branches won (by 4.6%).
  const double unclamped = total + (k.target - closing) * mass;
  const double wanted = kFriction ? std::max(unclamped, 0.0) : at_least_zero(unclamped);
  const double impulse = wanted - total;
  if (!kFriction || impulse != 0.0) {
    total = wanted;
    va -= n * (impulse * wa);
    if (!kFixed) vb += n * (impulse * wb);
    changed = changed | (std::fabs(impulse) > 1.0e-12);
  }
  if (kFriction && k.mu > 0.0) {
    changed = apply_contact_friction<kFixed>(k, va, vb, wa, wb, mass) || changed;
  }
}

// One marked candidate as a contact record (targets from the velocities before
// any impulse or cancellation of this phase).
// Forced inline: it is the body of the gather loop in restitution(), as it was when
// the runner was one class body (out of line, a call per contact made the step a few
// per cent slower).
__attribute__((always_inline)) inline void StepRunner::gather_contact(std::uint32_t c) {
  const Candidate& cand = w_.candidates_[c];
  const Body& a = body(cand.lower);
  const Body& b = body(cand.upper);
  ContactRecord& k = w_.contacts_[contact_count_++];
  k.lower = cand.lower;
  k.upper = cand.upper;
  k.lower_pos = cand.lower_pos;
  k.upper_pos = cand.upper_pos;
  k.normal = w_.contact_normal_[c];
  k.up = dot(k.normal, up_);
  k.inv_mass_lower = a.inv_mass;
  k.inv_mass_upper = cand.fixed ? 0.0 : b.inv_mass;
  const double closing = dot(b.velocity - a.velocity, k.normal);
  const double e = mix_restitution(a.restitution, b.restitution);
  k.target = closing < 0.0 ? -effective_restitution(-closing, e, rest_speed_) * closing : 0.0;
  // A near miss is a speculative contact: the pair may close its gap (down to
  // the slop it keeps) within this sub-step, and no more.
  if (w_.contact_near_miss_[c])
    k.target = -std::max(w_.contact_gap_[c] - near_miss_margin(), 0.0) / h_;
  k.mu = mix_contact_friction(a.contact_friction, b.contact_friction) *
         load_on(cand.fixed, a, b, k.up);
  const WarmEntry* warm =
      s_.warm_starting ? w_.warm_entry(cand.lower, cand.upper, b.generation) : nullptr;
  k.warm = warm != nullptr ? warm->impulse : 0.0;
  k.warm_tangent = warm != nullptr ? warm->tangent_impulse : 0.0;
  k.impulse = 0.0;
  k.tangent_impulse = 0.0;
  k.upper_generation = b.generation;
  k.fixed = cand.fixed;
  if (cand.fixed && b.is_dynamic()) wake_if_hit(cand, k, closing);
  if (lanes_) {
    // Shock propagation's weights depend on the contacts' angles and order alone,
    // so every iteration would find the same: the lanes take them from here.
    double wa = k.inv_mass_lower;
    double wb = k.inv_mass_upper;
    carry(cand.fixed, cand.lower_pos, cand.upper_pos, k.up, wa, wb);
    w_.contact_weights_[contact_count_ - 1] = {wa, wb};
  }
  if (hold_) {
    w_.in_contact_[cand.lower_pos] = 1;
    if (!cand.fixed) w_.in_contact_[cand.upper_pos] = 1;
  }
}

// Coulomb friction: the tangential impulse accumulated on a contact stays within
// mu times its normal impulse (a contact that pushes nothing holds nothing).
template <bool kFixed>
inline bool StepRunner::apply_contact_friction(ContactRecord& k, Vec2& va, Vec2& vb, double wa,
                                               double wb, double mass) {
  const Vec2 n = k.normal;
  const Vec2 t{-n.y, n.x};
  const double sliding = dot((kFixed ? Vec2{} : vb) - va, t);
  const double limit = k.mu * k.impulse;
  double& total = k.tangent_impulse;
  const double wanted = std::clamp(total - sliding * mass, -limit, limit);
  const double impulse = wanted - total;
  if (impulse == 0.0) return false;
  total = wanted;
  va -= t * (impulse * wa);
  if (!kFixed) vb += t * (impulse * wb);
  return std::fabs(impulse) > 1.0e-12;
}

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
inline void StepRunner::update_loads(std::span<const ContactRecord> contacts) {
  const std::size_t n = w_.active_.size();
  auto& own = w_.support_impulse_;
  auto& carried = w_.carried_impulse_;
  own.assign(n, 0.0);
  carried.assign(n, 0.0);
  for (const ContactRecord& k : contacts) {
    if (k.up < -kSupportCosine) own[k.lower_pos] -= k.impulse * k.up;
    if (k.up > kSupportCosine && !k.fixed) own[k.upper_pos] += k.impulse * k.up;
  }
  // A body whose supports pushed less than its weight (landing, or held by the
  // position passes) shares what it carries as if they had pushed its weight.
  const double weight = length(s_.gravity) * h_;  // a body's own push, per unit mass
  const auto factor = [&](std::uint32_t p) {
    const double resting = std::max(own[p], body(w_.active_[p]).mass * weight);
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
    body(w_.active_[p]).load = factor(p);
  }
}

// What the contacts did to a body's velocity this sub-step, per axis, is how
// much of its acceleration (gravity and its own) they held; the next sub-step
// applies it as a force from the start (the support and friction a resting body
// will get again). Only for a body that is resting after its contacts (no faster
// than the rest speed): an impact is no support. Per axis between 0 and the
// acceleration: contacts hold a body back, never pull it, and never hold it back
// harder than it is pushed.
inline void StepRunner::update_held() {
  for (std::size_t p = 0; p < w_.active_.size(); ++p) {
    if (scattered_) prefetch_ahead(p);
    update_held(p, body(w_.active_[p]));
  }
}

inline void StepRunner::update_held(std::size_t p, Body& b) const {
  if (!w_.in_contact_[p] || dot(b.velocity, b.velocity) > rest_speed_ * rest_speed_) {
    b.held = {};
    return;
  }
  const Vec2 a = driving_acceleration(b);  // hold_: gravity is on
  const Vec2 change = b.velocity - w_.velocity_before_contacts_[p];
  b.held = {held_part(change.x / h_, a.x), held_part(change.y / h_, a.y)};
}

// The part of a velocity change (per second) that held back an acceleration a.
inline double StepRunner::held_part(double change, double a) {
  return a < 0.0 ? std::clamp(change, 0.0, -a) : std::clamp(change, -a, 0.0);
}

// Each awake body keeps the impulses of the contacts it was the lower body of.
inline void StepRunner::remember_impulses() {
  // Contacts come grouped by the lower body's position: one walk rewrites the
  // pool in processing order.
  const std::span<const ContactRecord> contacts(w_.contacts_.data(), contact_count_);
  auto& pool = w_.warm_pool;
  pool.clear();
  std::size_t i = 0;
  for (std::uint32_t p = 0; p < w_.active_.size(); ++p) {
    const std::uint32_t slot = w_.active_[p];
    const auto first = static_cast<std::uint32_t>(pool.size());
    std::uint8_t count = 0;
    for (; i < contacts.size() && contacts[i].lower_pos == p; ++i) {
      const ContactRecord& k = contacts[i];
      if (!(k.impulse <= 0.0) && count < kWarmSlots) {
        pool.push_back({k.upper, k.upper_generation, k.impulse, k.tangent_impulse});
        ++count;
      }
    }
    w_.warm_first[slot] = first;
    w_.warm_count[slot] = count;
  }
}

// A body pushed back out of a penetration by something immovable loses the
// velocity that drove it in, up to correction / h, but gains none along the push. Without this a
// body jammed against others (a row pressed to a wall) keeps the velocity the
// contact iterations could not remove: it is put back in place every step while
// its velocity grows, and the pile never comes to rest.
inline Vec2 StepRunner::cancelled_velocity(Vec2 v, Vec2 correction, double per_second) {
  // Per axis, so that a push up from a floor cannot turn into sideways motion.
  for (int axis = 0; axis < 2; ++axis) {
    const double pushed = component(correction, axis);
    double& u = component(v, axis);
    if (pushed > 0.0 && u < 0.0) u = std::min(0.0, u + pushed * per_second);
    if (pushed < 0.0 && u > 0.0) u = std::max(0.0, u + pushed * per_second);
  }
  return v;
}

// A sleeping body wakes when it is hit: harder than a resting contact presses
// (from above), or at all from the side or below. From above means any contact
// on its upper side, a steep one too: a body resting there closes on it by up to
// the g*h it gained in the sub-step, which is no hit.
inline void StepRunner::wake_if_hit(const Candidate& cand, const ContactRecord& contact,
                                    double closing) {
  const bool resting_on_it = contact.up < 0.0;
  if (-closing > wake_speed(resting_on_it)) w_.to_wake_.push_back(cand.upper);
}

}  // namespace phys
