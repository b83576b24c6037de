#pragma once
// Who hears of which contact events (Hello.contacts, docs/PROTOCOL.md "Contact
// events"): the check of a subscription, the match of an event against it, and an
// event as a message.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "physics/contact_events.h"
#include "physics/sensor_events.h"
#include "wire.pb.h"

namespace server {

// Bodies a spectator may list, at most.
inline constexpr std::size_t kMaxContactBodies = 64;
// Events in one snapshot, at most; the rest wait for the next one.
inline constexpr std::size_t kMaxContactEventsPerSnapshot = 256;
// Events waiting for a client, at most: more are dropped (and counted in the next
// snapshot's contact_events_dropped), so a client that reads nothing costs bounded
// memory.
inline constexpr std::size_t kMaxPendingContactEvents = 1024;

struct ContactFilter {
  enum class Kind : std::uint8_t { OwnBody, All, Bodies };
  Kind kind = Kind::OwnBody;
  std::vector<std::uint64_t> bodies;  // Bodies: packed ids, ascending, each once

  // Whether the event is one of the subscribed bodies' (own: the player's body).
  bool matches(const phys::ContactEvent& event, std::optional<std::uint64_t> own) const;
};

// Checks a Hello's subscription: empty when accepted (and `filter` set), else what
// is wrong, for ERROR_INVALID_SUBSCRIPTION.
std::string resolve_contacts(const physics::wire::ContactSubscription& request, bool spectator,
                             ContactFilter& filter);

void fill_contact_event(const phys::ContactEvent& event, physics::wire::ContactEvent& out);

// Sensor events (Hello.sensor_events) go to a subscriber as contact events do, with
// the same limits: at most this many in one snapshot, this many waiting.
inline constexpr std::size_t kMaxSensorEventsPerSnapshot = kMaxContactEventsPerSnapshot;
inline constexpr std::size_t kMaxPendingSensorEvents = kMaxPendingContactEvents;

void fill_sensor_event(const phys::SensorEvent& event, physics::wire::SensorEvent& out);

}  // namespace server
