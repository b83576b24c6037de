// The velocity solver: sequential impulses over the contacts the moves and the
// position passes marked (restitution, contact friction, shock propagation, warm
// start), and what the contacts held of each body's acceleration.
// Reads: the candidates, scratch.marks and (with kinematic bodies) the pinned
// bodies, the bodies, the warm-start pool.
// Writes: the bodies' velocities, held accelerations and loads; the warm-start
// pool; scratch.velocity (its contact records, handed on to sleep) and to_wake.
// This file gathers the contacts and runs the iterations; the impulses on one
// contact are contact_impulses.h's.
#include <algorithm>
#include <cmath>

#include "contact_impulses.h"
#include "step_phases.h"
#include "step_shared.h"

namespace phys {

namespace {

class VelocitySolver : StepPhase {
 public:
  VelocitySolver(const StepContext& ctx, WorldImpl& world, const Order& order,
                 const FreeMotion& motion)
      : StepPhase(ctx, world),
        scattered_(order.scattered),
        any_contact_friction_(motion.any_contact_friction),
        kinematic_(world.kinematic_count() != 0) {}
  std::span<const ContactRecord> run();

 private:
  void gather_contacts(std::uint32_t active);
  void iterate(std::span<ContactRecord> contacts, std::uint32_t active);
  void gather_contact(std::uint32_t c);
  void update_held();
  void update_held(std::size_t p, Body& b) const;
  static double held_part(double change, double a);
  static Vec2 cancelled_velocity(Vec2 v, Vec2 correction, double per_second);
  void wake_if_hit(const Candidate& cand, const ContactRecord& contact, double closing);
  bool held_off(std::uint32_t c) const;
  void stop_pinned_bodies();

  const bool scattered_;             // the processing order is far from slot order
  const bool any_contact_friction_;  // an awake body has contact friction
  // The world has kinematic bodies: contacts with them carry their velocity (and
  // only then is ContactRecord::upper_slide written and read).
  const bool kinematic_;
  bool lanes_ = false;               // the iterations run in ContactLanes
  std::uint32_t contact_count_ = 0;  // records in use at the front of scratch.velocity.contacts
};

// The velocity component along each contact's normal is reflected and scaled by
// the restitution (zeroed below the rest speed), impulses split by inverse mass.
std::span<const ContactRecord> VelocitySolver::run() {
  const auto active = static_cast<std::uint32_t>(w_.lists.active.size());
  gather_contacts(active);
  if (contact_count_ == 0) {  // no contact holds anything
    if (c_.hold) update_held();
    if (kinematic_) stop_pinned_bodies();
    return {};
  }
  ++w_.counters.velocity_solves;
  const std::span<ContactRecord> contacts(x_.velocity.contacts.data(), contact_count_);
  iterate(contacts, active);
  // The velocities go back to the bodies; what the contacts held of each one's
  // acceleration is found in the same walk (update_held's, while the body is in cache).
  const auto& velocity = x_.velocity.solver_velocity;
  for (std::uint32_t p = 0; p < active; ++p) {
    if (scattered_) prefetch_ahead(p);
    Body& b = body(w_.lists.active[p]);
    b.velocity = velocity[p];
    if (c_.hold) update_held(p, b);
  }
  if (kinematic_) stop_pinned_bodies();
  return contacts;
}

// The contact records of this sub-step, and the dense copy of the awake bodies'
// velocities the iterations work on.
inline void VelocitySolver::gather_contacts(std::uint32_t active) {
  // Records are written in place: the array only grows (no clearing, no growth
  // check per contact), contact_count_ says how many are this sub-step's.
  if (x_.velocity.contacts.size() < w_.candidates.list.size()) {
    x_.velocity.contacts.resize(w_.candidates.list.size());
  }
  contact_count_ = 0;
  // Without friction, the iterations run two contacts at a time, with the same
  // results (ContactLanes). Shock propagation's weights for them are found as the
  // contacts are gathered, in the same order.
  lanes_ = kHaveContactLanes && s_.simd_contact_lanes && !any_contact_friction_;
  if (lanes_) {
    if (x_.velocity.contact_weights.size() < w_.candidates.list.size()) {
      x_.velocity.contact_weights.resize(w_.candidates.list.size());
    }
    x_.supported.assign(w_.lists.active.size(), 0);
  }
  // Gather the marked candidates in candidate order, with what the iterations read.
  // Candidates come grouped by their lower body's position p, and a body is never
  // read again once its group is done (later groups hold only higher bodies), so
  // its velocity is cancelled into its corrections right there, while it is in
  // cache. With no contact at all every correction is zero and that changes nothing.
  const double per_second = 1.0 / c_.h;
  const auto candidate_count = static_cast<std::uint32_t>(w_.candidates.list.size());
  // The iterations read and write only awake bodies' velocities (a fixed body's
  // counts as zero): they work on a dense copy by position, written back at the end.
  // One velocity more, always zero: what a fixed body's lane reads (ContactLanes).
  auto& velocity = x_.velocity.solver_velocity;
  velocity.resize(active + 1);
  velocity[active] = {};
  if (c_.hold) {  // what the contacts will do along "up" is measured from here
    x_.velocity.before_contacts.resize(active);
    x_.velocity.in_contact.assign(active, 0);
  }
  const bool pins = kinematic_ && !x_.position.pinned.empty();
  for (std::uint32_t p = 0; p < active; ++p) {
    if (scattered_) prefetch_ahead(p);
    for (std::uint32_t c = w_.candidates.first[p]; c < w_.candidates.first[p + 1]; ++c) {
      // The upper bodies are anywhere in memory, as the lower ones are.
      if (scattered_ && c + kPrefetchAhead < candidate_count) {
        __builtin_prefetch(&w_.bodies[w_.candidates.list[c + kPrefetchAhead].upper]);
      }
      if (x_.marks.contact_of[c] != kNone && !(pins && held_off(c))) gather_contact(c);
    }
    // Cancelled in a register and stored whole: reading back a velocity just
    // stored one half at a time stalls the load.
    Body& b = body(w_.lists.active[p]);
    if (c_.hold) x_.velocity.before_contacts[p] = b.velocity;
    const Vec2 v = cancelled_velocity(b.velocity, b.correction, per_second);
    b.velocity = v;
    velocity[p] = v;
  }
}

// The iterations over the contacts (contact_impulses.h, or ContactLanes two at a
// time), until one changes nothing.
inline void VelocitySolver::iterate(std::span<ContactRecord> contacts, std::uint32_t active) {
  Vec2* const solver = x_.velocity.solver_velocity.data();
  const bool shock = c_.shock;
  if (lanes_) {
    const std::span<const ContactWeights> weights(x_.velocity.contact_weights.data(),
                                                  contact_count_);
    x_.velocity.lanes.pack(contacts, weights, active);
  }
  for (int iteration = 0; iteration < s_.velocity_iterations; ++iteration) {
    bool changed = false;
    if (lanes_) {
      changed = x_.velocity.lanes.iterate(solver, iteration == 0);
    } else {
      x_.supported.assign(w_.lists.active.size(), 0);
      std::uint8_t* const supported = x_.supported.data();
      if (any_contact_friction_) {
        if (kinematic_) {
          solve_contacts<true, true>(contacts, solver, supported, shock, iteration == 0, changed);
        } else {
          solve_contacts<true, false>(contacts, solver, supported, shock, iteration == 0, changed);
        }
      } else {
        solve_contacts<false, false>(contacts, solver, supported, shock, iteration == 0, changed);
      }
    }
    if (!changed && iteration > 0) break;
  }
  if (lanes_) x_.velocity.lanes.unpack(contacts);
}

// One marked candidate as a contact record (targets from the velocities before
// any impulse or cancellation of this phase).
// Forced inline: it is the body of the gather loop in run(), as it was when
// the runner was one class body (out of line, a call per contact made the step a few
// per cent slower).
__attribute__((always_inline)) inline void VelocitySolver::gather_contact(std::uint32_t c) {
  const Candidate& cand = w_.candidates.list[c];
  const Body& a = body(cand.lower);
  const Body& b = body(cand.upper);
  ContactRecord& k = x_.velocity.contacts[contact_count_++];
  k.lower = cand.lower;
  k.upper = cand.upper;
  k.lower_pos = cand.lower_pos;
  k.upper_pos = cand.upper_pos;
  k.normal = x_.marks.normal[c];
  k.up = dot(k.normal, c_.up);
  k.inv_mass_lower = a.inv_mass;
  k.inv_mass_upper = cand.fixed ? 0.0 : b.inv_mass;
  const double closing = dot(b.velocity - a.velocity, k.normal);
  const double e = mix_restitution(a.restitution, b.restitution);
  k.target = closing < 0.0 ? -effective_restitution(-closing, e, c_.rest_speed) * closing : 0.0;
  // A near miss is a speculative contact: the pair may close its gap (down to
  // the slop it keeps) within this sub-step, and no more.
  if (x_.marks.near_miss[c]) k.target = -std::max(x_.marks.gap[c] - near_miss_margin(), 0.0) / c_.h;
  // A kinematic body is fixed for the iterations (its velocity counts as zero, as a
  // static body's), so its motion is given as the contact's: the target closing
  // velocity is measured against it, and the sliding (upper_slide) too. This is how
  // it pushes what it meets and carries what rests on it.
  if (kinematic_) {
    k.upper_slide = 0.0;
    if (cand.fixed && b.motion == Motion::Kinematic) {
      k.target -= dot(b.velocity, k.normal);
      k.upper_slide = dot(b.velocity, Vec2{-k.normal.y, k.normal.x});
    }
  }
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
    x_.velocity.contact_weights[contact_count_ - 1] = {wa, wb};
  }
  if (c_.hold) {
    x_.velocity.in_contact[cand.lower_pos] = 1;
    if (!cand.fixed) x_.velocity.in_contact[cand.upper_pos] = 1;
  }
}

// What the contacts did to a body's velocity this sub-step, per axis, is how
// much of its acceleration (gravity and its own) they held; the next sub-step
// applies it as a force from the start (the support and friction a resting body
// will get again). Only for a body that is resting after its contacts (no faster
// than the rest speed): an impact is no support. Per axis between 0 and the
// acceleration: contacts hold a body back, never pull it, and never hold it back
// harder than it is pushed.
inline void VelocitySolver::update_held() {
  for (std::size_t p = 0; p < w_.lists.active.size(); ++p) {
    if (scattered_) prefetch_ahead(p);
    update_held(p, body(w_.lists.active[p]));
  }
}

inline void VelocitySolver::update_held(std::size_t p, Body& b) const {
  if (!x_.velocity.in_contact[p] || dot(b.velocity, b.velocity) > c_.rest_speed * c_.rest_speed) {
    b.held = {};
    return;
  }
  const Vec2 a = driving_acceleration(b);  // c_.hold: gravity is on
  const Vec2 change = b.velocity - x_.velocity.before_contacts[p];
  b.held = {held_part(change.x / c_.h, a.x), held_part(change.y / c_.h, a.y)};
}

// The part of a velocity change (per second) that held back an acceleration a.
inline double VelocitySolver::held_part(double change, double a) {
  return a < 0.0 ? std::clamp(change, 0.0, -a) : std::clamp(change, -a, 0.0);
}

// A body pushed back out of a penetration by something immovable loses the
// velocity that drove it in, up to correction / h, but gains none along the push. Without this a
// body jammed against others (a row pressed to a wall) keeps the velocity the
// contact iterations could not remove: it is put back in place every step while
// its velocity grows, and the pile never comes to rest.
inline Vec2 VelocitySolver::cancelled_velocity(Vec2 v, Vec2 correction, double per_second) {
  // Per axis, so that a push up from a floor cannot turn into sideways motion.
  for (int axis = 0; axis < 2; ++axis) {
    const double pushed = component(correction, axis);
    double& u = component(v, axis);
    if (pushed > 0.0 && u < 0.0) u = std::min(0.0, u + pushed * per_second);
    if (pushed < 0.0 && u > 0.0) u = std::max(0.0, u + pushed * per_second);
  }
  return v;
}

// The contact of a pinned body (step_crush.cpp) with a kinematic body pushing it
// toward the static one is left out, as the position passes left out its push:
// kept, it and the static contact would push the body both ways, their impulses
// growing every sub-step while it stays pinned, and the warm start would hand the
// kinematic one's pull on to the body once the kinematic body turned back.
inline bool VelocitySolver::held_off(std::uint32_t c) const {
  const Candidate& cand = w_.candidates.list[c];
  if (!cand.fixed || body(cand.upper).motion != Motion::Kinematic) return false;
  return dot(x_.marks.normal[c], x_.position.pin_normal[cand.lower_pos]) < 0.0;
}

// A body pinned against a static body by a kinematic one (step_crush.cpp) keeps no
// velocity into the static body: the kinematic contact gave it the kinematic body's,
// whose push the position passes held off.
inline void VelocitySolver::stop_pinned_bodies() {
  for (const std::uint32_t p : x_.position.pinned) {
    Body& b = body(w_.lists.active[p]);
    const Vec2 wall = x_.position.pin_normal[p];
    const double into = dot(b.velocity, wall);
    if (into > 0.0) b.velocity -= wall * into;
  }
}

// A sleeping body wakes when it is hit: harder than a resting contact presses
// (from above), or at all from the side or below. From above means any contact
// on its upper side, a steep one too: a body resting there closes on it by up to
// the g*h it gained in the sub-step, which is no hit.
inline void VelocitySolver::wake_if_hit(const Candidate& cand, const ContactRecord& contact,
                                        double closing) {
  const bool resting_on_it = contact.up < 0.0;
  if (-closing > wake_speed(resting_on_it)) x_.to_wake.push_back(cand.upper);
}

}  // namespace

std::span<const ContactRecord> solve_velocities(const StepContext& ctx, WorldImpl& w,
                                                const Order& order, const FreeMotion& motion) {
  return VelocitySolver(ctx, w, order, motion).run();
}

}  // namespace phys
