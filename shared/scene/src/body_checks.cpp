// A body's checks: name, shape and size, position, velocity and acceleration,
// static, kinematic or dynamic, mass, restitution and friction, filter and sensor;
// and its placement in bounds.
#include "body_checks.h"

#include <fmt/format.h>

#include <cstdint>
#include <string>
#include <utility>

namespace scene::detail {

namespace proto = physics::scene;

namespace {

phys::Vec2 half_size(const phys::BodyDef& body) {
  return body.shape == phys::Shape::Circle ? phys::Vec2{body.radius, body.radius}
                                           : body.half_extents;
}

std::string describe_bounds(const phys::Aabb& bounds) {
  return fmt::format("world.bounds [({}, {}), ({}, {})]", bounds.min.x, bounds.min.y, bounds.max.x,
                     bounds.max.y);
}

// The filter's bits are 32 wide in the core (phys::Filter); the format leaves room.
bool check_bits(Checker& check, const FieldPath& path, std::uint64_t bits, std::uint32_t* out) {
  if (bits > 0xFFFFFFFFu)
    return check.fail(path, fmt::format("is {:#x}: categories are 32 bits wide, so at most "
                                        "0xffffffff",
                                        bits));
  *out = static_cast<std::uint32_t>(bits);
  return true;
}

bool check_filter(Checker& check, const proto::Body& body, const FieldPath& path,
                  phys::Filter* out) {
  phys::Filter filter;
  if (body.has_category_bits() &&
      !check_bits(check, path.child("category_bits"), body.category_bits(), &filter.category_bits))
    return false;
  if (body.has_mask_bits() &&
      !check_bits(check, path.child("mask_bits"), body.mask_bits(), &filter.mask_bits))
    return false;
  filter.group = body.group();
  *out = filter;
  return true;
}

}  // namespace

bool inside_bounds(const phys::WorldSettings& settings, const phys::BodyDef& body) {
  if (!settings.has_bounds) return true;
  const phys::Vec2 half = half_size(body);
  const phys::Aabb& bounds = settings.bounds;
  return body.position.x - half.x >= bounds.min.x && body.position.x + half.x <= bounds.max.x &&
         body.position.y - half.y >= bounds.min.y && body.position.y + half.y <= bounds.max.y;
}

// One check per Body field in the scene format's order, each filling the BodyDef as it
// passes: as long as the message is.
bool check_body(Checker& check, const proto::Body& body, const FieldPath& path,
                const phys::WorldSettings& settings, bool is_template, phys::BodyDef* out) {
  if (!check_name(check, path.child("name"), body.name())) return false;
  phys::BodyDef def;
  switch (body.shape_case()) {
    case proto::Body::kCircle: {
      const FieldPath radius = path.child("circle").child("radius");
      if (!check.positive(radius, body.circle().radius())) return false;
      if (!check.at_most(radius, body.circle().radius(), settings.max_body_size,
                         "the core's largest body size"))
        return false;
      def.shape = phys::Shape::Circle;
      def.radius = body.circle().radius();
      break;
    }
    case proto::Body::kBox: {
      const FieldPath half = path.child("box").child("half_extents");
      for (const auto& [axis, value] : {std::pair{"x", body.box().half_extents().x()},
                                        std::pair{"y", body.box().half_extents().y()}}) {
        if (!check.positive(half.child(axis), value)) return false;
        if (!check.at_most(half.child(axis), value, settings.max_body_size,
                           "the core's largest body size"))
          return false;
      }
      def.shape = phys::Shape::Box;
      def.half_extents = to_vec(body.box().half_extents());
      break;
    }
    case proto::Body::SHAPE_NOT_SET:
      return check.fail(path,
                        "has no shape: write circle { radius: R } or "
                        "box { half_extents { x: HX y: HY } }");
  }
  def.name = body.name();
  if (body.is_static() && body.is_kinematic())
    return check.fail(path.child("is_kinematic"),
                      "a body is static or kinematic, not both (is_static is set too)");
  def.motion = body.is_static()      ? phys::Motion::Static
               : body.is_kinematic() ? phys::Motion::Kinematic
                                     : phys::Motion::Dynamic;
  if (is_template && body.has_position())
    return check.fail(path.child("position"),
                      "must be unset: this template's positions come from its grid or "
                      "from the spawn points");
  if (!check.coordinate(path.child("position"), body.position())) return false;
  def.position = to_vec(body.position());

  if (!check.finite(path.child("velocity"), body.velocity())) return false;
  def.velocity = to_vec(body.velocity());
  if (!check.at_most(path.child("velocity"), phys::length(def.velocity), settings.max_speed,
                     "world.max_speed"))
    return false;
  if (!check.finite(path.child("acceleration"), body.acceleration())) return false;
  def.acceleration = to_vec(body.acceleration());
  if (!check.at_most(path.child("acceleration"), phys::length(def.acceleration),
                     settings.max_acceleration, "the core's acceleration limit"))
    return false;

  if (body.is_static()) {
    if (body.has_mass())
      return check.fail(path.child("mass"),
                        "must be unset on a static body (static bodies have infinite mass)");
    if (def.velocity != phys::Vec2{})
      return check.fail(path.child("velocity"), "must be unset: a static body never moves");
    if (def.acceleration != phys::Vec2{})
      return check.fail(path.child("acceleration"), "must be unset: a static body never moves");
  } else if (body.is_kinematic()) {
    if (body.has_mass())
      return check.fail(path.child("mass"),
                        "must be unset on a kinematic body (kinematic bodies have infinite mass)");
    if (def.acceleration != phys::Vec2{})
      return check.fail(path.child("acceleration"),
                        "must be unset: a kinematic body moves by its velocity alone");
  } else if (body.has_mass()) {
    if (!check.positive(path.child("mass"), body.mass())) return false;
    def.mass = body.mass();
  }
  if (!check.in_range(path.child("restitution"), body.restitution(), 0.0, 1.0)) return false;
  def.restitution = body.restitution();
  const FieldPath friction = path.child("friction");
  if (!check.not_negative(friction.child("x"), body.friction().x()) ||
      !check.not_negative(friction.child("y"), body.friction().y()))
    return false;
  def.friction = to_vec(body.friction());
  if (!check.not_negative(path.child("contact_friction"), body.contact_friction())) return false;
  def.contact_friction = body.contact_friction();
  if (!check_filter(check, body, path, &def.filter)) return false;
  def.is_sensor = body.is_sensor();
  *out = def;
  return true;
}

bool check_inside(Checker& check, const FieldPath& path, const phys::WorldSettings& settings,
                  const phys::BodyDef& body, std::string_view what) {
  if (inside_bounds(settings, body)) return true;
  return check.fail(path, fmt::format("{} at ({}, {}) lies outside {}", what, body.position.x,
                                      body.position.y, describe_bounds(settings.bounds)));
}

}  // namespace scene::detail
