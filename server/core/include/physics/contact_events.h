#pragma once
// Contact events: the begin and the end of contact between two bodies, produced
// by the step itself (World::set_contact_events), so that they are as reproducible
// as the state.
//
// Contact. Two bodies are in contact in a step when, in at least one of its
// sub-steps, either
//   - a swept move of one of them stopped at the time of impact against the other
//     (a static or sleeping body), or
//   - after the sub-step's position passes (before the contact solver), their
//     shapes overlap or are apart by at most twice the slop (the margin within
//     which the solver treats a pair as resting on each other; a resting pair is
//     left one slop apart).
// Begin: the first step a pair is in contact. End: the first step it is not, with
// this exception: a pair in which neither body was stepped (each is static or
// asleep, or was asleep all step) keeps its contact, so falling asleep ends
// nothing and waking begins nothing. A removed body's contacts end at the next step.
// Switching events on starts from no contact: pairs already touching begin at the
// first step they are seen, a pair of sleeping bodies once one of them wakes.
#include <cstdint>

#include "physics/body.h"
#include "physics/vec2.h"

namespace phys {

enum class ContactEventKind : std::uint8_t { Begin, End };

struct ContactEvent {
  ContactEventKind kind = ContactEventKind::Begin;
  // World::step_count() after the step that produced it (the first step is 1).
  std::uint64_t step = 0;
  // The pair, a.index < b.index.
  BodyId a;
  BodyId b;
  // Begin: where the shapes touch when the contact is first seen (the midpoint of
  // the gap or the overlap between the two surfaces along the normal). End: the
  // point of the last step in contact.
  Vec2 point{};
  // Unit normal from a toward b, when and as `point`.
  Vec2 normal{};
  // m/s, the relative velocity along the normal, positive when the bodies approach:
  // -dot(v_b - v_a, normal). Begin: before the contact solver acts on the pair (for
  // a swept hit, at the time of impact; otherwise after the sub-step's moves). End:
  // after the step (negative when the bodies separate; a removed body counts as
  // still).
  double closing_speed = 0.0;

  bool operator==(const ContactEvent&) const = default;
};

}  // namespace phys
