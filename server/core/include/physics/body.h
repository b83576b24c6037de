#pragma once
// What a body is made from (BodyDef, with documented defaults) and how it is named
// (BodyId: an index plus a generation, so a stale id is detected, not misused).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "physics/vec2.h"

namespace phys {

enum class Shape : std::uint8_t { Circle, Box };
// Static: never moves, infinite mass. Dynamic: moved by gravity, its acceleration
// and its contacts. Kinematic: moved by its velocity alone (set by code), with
// infinite mass: it pushes and carries dynamic bodies, and nothing pushes it back;
// it meets neither static nor other kinematic bodies. A dynamic body it pins
// against a static body is crushed: the static body wins, the dynamic body stays on
// its near side and the kinematic body overlaps it, and World::crush_events reports
// it (physics/crush_events.h).
enum class Motion : std::uint8_t { Static, Dynamic, Kinematic };

// Which pairs of bodies may collide (Box2D's b2Filter). Two bodies of the same
// non-zero group always collide (positive group) or never do (negative group);
// otherwise they collide when each one's mask holds a category bit of the other.
// The default puts a body in category 1 and lets it meet every category: every
// pair collides, as without filtering.
struct Filter {
  std::uint32_t category_bits = 0x1;
  std::uint32_t mask_bits = 0xFFFFFFFFu;
  std::int32_t group = 0;
  constexpr bool operator==(const Filter&) const = default;
};

constexpr bool should_collide(const Filter& a, const Filter& b) {
  if (a.group == b.group && a.group != 0) return a.group > 0;
  return (a.mask_bits & b.category_bits) != 0 && (b.mask_bits & a.category_bits) != 0;
}

// The longest body name, in bytes (the scene format's limit for names).
inline constexpr std::size_t kMaxBodyNameBytes = 256;

struct BodyDef {
  Shape shape = Shape::Box;
  Motion motion = Motion::Dynamic;
  Vec2 position{};
  Vec2 velocity{};
  // The input a client sets; it holds until it is set again.
  Vec2 acceleration{};
  double radius = 0.5;          // circles only
  Vec2 half_extents{0.5, 0.5};  // boxes only
  double mass = 1.0;            // dynamic only; static bodies have infinite mass
  double restitution = 0.0;     // 0 stops, 1 keeps the normal speed
  Vec2 friction{};              // per axis, the velocity decay rate in 1/s
  // Coulomb friction between touching bodies (beyond the classic recipe): the tangential
  // impulse of a contact is at most this times its normal impulse. 0 is frictionless.
  double contact_friction = 0.0;
  // Which bodies it may collide with (and, for a sensor, which it detects).
  Filter filter{};
  // A sensor detects the bodies it overlaps (World::sensor_events) and collides with
  // none: nothing pushes it and it pushes nothing. Any motion may be a sensor.
  bool is_sensor = false;
  // A label for code and people (World::find_body); need not be unique. Empty: none.
  std::string name;
};

// The half size of the box a body occupies: a circle's is (radius, radius), a box's its
// half extents.
constexpr Vec2 half_size(Shape shape, double radius, Vec2 half_extents) {
  return shape == Shape::Circle ? Vec2{radius, radius} : half_extents;
}

// Why a BodyDef was refused. Every value names the field at fault.
enum class BodyDefError : std::uint8_t {
  None,
  NonFinitePosition,
  NonFiniteVelocity,
  NonFiniteAcceleration,
  BadRadius,              // not finite, or <= 0
  BadHalfExtents,         // not finite, or <= 0
  BadMass,                // dynamic body whose mass is not finite or <= 0 (a kinematic
                          // or static body's mass is ignored: it is infinite)
  BadRestitution,         // not finite, < 0 or > 1
  BadFriction,            // not finite, or < 0
  OutOfBounds,            // outside the world's bounds, when it has bounds
  TooLarge,               // larger than the world's size limit
  TooManyBodies,          // the world is full
  KinematicAcceleration,  // a kinematic body moves by its velocity alone: must be zero
  BadName,                // longer than kMaxBodyNameBytes
};

std::string_view describe(BodyDefError error);

struct BodyId {
  std::uint32_t index = UINT32_MAX;
  std::uint32_t generation = 0;

  static constexpr BodyId invalid() { return {}; }
  constexpr bool is_valid() const { return index != UINT32_MAX; }
  constexpr bool operator==(const BodyId&) const = default;
  // Packs into 64 bits so that an id can travel in a message as it is.
  constexpr std::uint64_t packed() const {
    return (static_cast<std::uint64_t>(generation) << 32) | index;
  }
  static constexpr BodyId from_packed(std::uint64_t bits) {
    return {static_cast<std::uint32_t>(bits), static_cast<std::uint32_t>(bits >> 32)};
  }
};

// A read-only view of one body, as the world holds it after the last step.
struct BodyState {
  BodyId id;
  Shape shape = Shape::Box;
  Motion motion = Motion::Dynamic;
  Vec2 position{};
  Vec2 velocity{};
  Vec2 acceleration{};
  double radius = 0.0;
  Vec2 half_extents{};
  double mass = 0.0;  // 0 for static and kinematic bodies (infinite mass)
  double restitution = 0.0;
  Vec2 friction{};
  double contact_friction = 0.0;
  bool awake = true;
};

}  // namespace phys
