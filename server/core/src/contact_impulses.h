#pragma once
// Sequential impulses on one contact record, the velocity solver's inner loop
// (step_velocity.cpp; ContactLanes runs the same without friction, two contacts at
// a time): the normal impulse with restitution's target, shock propagation's
// weights, the warm start, and Coulomb friction. On the solver's dense velocities
// by position, with no world: the solver gathers the records, these solve them.
// In an unnamed namespace, as they were when they were the solver's own: internal
// linkage, for the compiler to inline them into the solver's loops as it did then.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

#include "branchless.h"
#include "step_records.h"
#include "step_shared.h"

namespace phys {
namespace {

// Coulomb friction: the tangential impulse accumulated on a contact stays within
// mu times its normal impulse (a contact that pushes nothing holds nothing).
template <bool kFixed, bool kKinematic>
inline bool apply_contact_friction(ContactRecord& k, Vec2& va, Vec2& vb, double wa, double wb,
                                   double mass) {
  const Vec2 n = k.normal;
  const Vec2 t{-n.y, n.x};
  double sliding = dot((kFixed ? Vec2{} : vb) - va, t);
  if (kFixed && kKinematic) sliding += k.upper_slide;
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

// One contact in one iteration of the velocity solver, built apart for contacts
// with a fixed body (no velocity of its own) and between two awake bodies, so
// that neither carries the other's tests.
template <bool kFixed, bool kFriction, bool kKinematic>
inline void solve_contact(ContactRecord& k, Vec2* solver, std::uint8_t* supported, bool shock,
                          bool first_iteration, bool& changed) {
  Vec2 fixed_velocity{};  // what vb names for a fixed body; never read
  Vec2& va = solver[k.lower_pos];
  Vec2& vb = kFixed ? fixed_velocity : solver[k.upper_pos];
  const Vec2 n = k.normal;
  double wa = k.inv_mass_lower;
  double wb = k.inv_mass_upper;
  phys::carry(supported, shock, kFixed, k.lower_pos, k.upper_pos, k.up, wa, wb);
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
      apply_contact_friction<kFixed, kKinematic>(k, va, vb, wa, wb, mass);
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
    changed = apply_contact_friction<kFixed, kKinematic>(k, va, vb, wa, wb, mass) || changed;
  }
}

// One iteration over the contacts. Built apart for scenes with contact friction
// and without (kFriction): without it, no contact has friction to apply.
template <bool kFriction, bool kKinematic>
inline void solve_contacts(std::span<ContactRecord> contacts, Vec2* solver, std::uint8_t* supported,
                           bool shock, bool first_iteration, bool& changed) {
  for (ContactRecord& k : contacts) {
    if (k.fixed) {
      solve_contact<true, kFriction, kKinematic>(k, solver, supported, shock, first_iteration,
                                                 changed);
    } else {
      solve_contact<false, kFriction, kKinematic>(k, solver, supported, shock, first_iteration,
                                                  changed);
    }
  }
}

}  // namespace
}  // namespace phys
