#include "portable/flat_world.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iterator>

namespace portable {
namespace {

double flag(bool on) { return on ? 1.0 : 0.0; }

// Reads the fields in order; the first bad one sets `error` and later reads return 0.
class Reader {
 public:
  // Reads from values[first] on; messages number the values from the array's start.
  Reader(std::span<const double> values, std::size_t first) : values_(values), at_(first) {}

  double number(const char* field) {
    if (!error_.empty()) return 0.0;
    if (at_ >= values_.size()) {
      fail(field, "missing");
      return 0.0;
    }
    return values_[at_++];
  }
  std::int64_t whole(const char* field, std::int64_t lo, std::int64_t hi) {
    const std::size_t index = at_;
    const double value = number(field);
    if (!error_.empty()) return 0;
    if (!(value >= static_cast<double>(lo) && value <= static_cast<double>(hi)) ||
        value != std::floor(value)) {
      error_ = "value " + std::to_string(index) + " (" + field + ") must be a whole number in [" +
               std::to_string(lo) + ", " + std::to_string(hi) + "]";
      return 0;
    }
    return static_cast<std::int64_t>(value);
  }
  bool on(const char* field) { return whole(field, 0, 1) == 1; }
  phys::Vec2 vec(const char* field) {
    const double x = number(field);
    return {x, number(field)};
  }

  const std::string& error() const { return error_; }
  void fail(const char* field, const std::string& why) {
    if (error_.empty()) error_ = "value " + std::to_string(at_) + " (" + field + "): " + why;
  }

 private:
  std::span<const double> values_;
  std::size_t at_;
  std::string error_;
};

void read_settings(Reader& in, phys::WorldSettings& s) {
  s.gravity = in.vec("gravity");
  s.integrator = static_cast<phys::Integrator>(in.whole("integrator", 0, 2));
  s.substeps = static_cast<int>(in.whole("substeps", 1, 64));
  s.slop = in.number("slop");
  s.position_iterations = static_cast<int>(in.whole("position iterations", 1, 64));
  s.velocity_iterations = static_cast<int>(in.whole("velocity iterations", 1, 64));
  s.warm_starting = in.on("warm starting");
  s.continuous = in.on("continuous");
  s.shock_propagation = in.on("shock propagation");
  s.hold_resting_support = in.on("hold resting support");
  s.rest_speed = in.number("rest speed");
  s.max_speed = in.number("max speed");
  s.max_acceleration = in.number("max acceleration");
  s.sleeping = in.on("sleeping");
  s.sleep_speed = in.number("sleep speed");
  s.sleep_time = in.number("sleep time");
  s.has_bounds = in.on("has bounds");
  s.bounds.min = in.vec("bounds min");
  s.bounds.max = in.vec("bounds max");
  s.max_body_size = in.number("max body size");
  s.max_bodies = static_cast<std::uint32_t>(in.whole("max bodies", 1, 1 << 20));
  s.simd_contact_lanes = in.on("simd contact lanes");
}

phys::BodyDef read_body(Reader& in, bool with_filters) {
  phys::BodyDef b;
  b.shape = in.whole("shape", 0, 1) == 0 ? phys::Shape::Circle : phys::Shape::Box;
  const std::int64_t motion = in.whole("motion", 0, with_filters ? 2 : 1);
  b.motion = motion == 0   ? phys::Motion::Static
             : motion == 1 ? phys::Motion::Dynamic
                           : phys::Motion::Kinematic;
  b.position = in.vec("position");
  b.velocity = in.vec("velocity");
  b.acceleration = in.vec("acceleration");
  b.radius = in.number("radius");
  b.half_extents = in.vec("half extents");
  b.mass = in.number("mass");
  b.restitution = in.number("restitution");
  b.friction = in.vec("friction");
  b.contact_friction = in.number("contact friction");
  if (with_filters) {
    b.filter.category_bits = static_cast<std::uint32_t>(in.whole("category bits", 0, UINT32_MAX));
    b.filter.mask_bits = static_cast<std::uint32_t>(in.whole("mask bits", 0, UINT32_MAX));
    b.filter.group = static_cast<std::int32_t>(in.whole("group", INT32_MIN, INT32_MAX));
    b.is_sensor = in.on("sensor");
  }
  return b;
}

// Whether a body needs version 2's fields.
bool needs_filters(const phys::BodyDef& b) {
  return b.motion == phys::Motion::Kinematic || b.is_sensor || b.filter != phys::Filter{};
}

}  // namespace

std::vector<double> flatten(const FlatWorld& world) {
  const phys::WorldSettings& s = world.settings;
  bool with_filters = false;
  for (const phys::BodyDef& b : world.bodies) with_filters = with_filters || needs_filters(b);
  std::vector<double> out = {
      with_filters ? kFlatVersionWithFilters : kFlatVersion,
      s.gravity.x,
      s.gravity.y,
      static_cast<double>(static_cast<int>(s.integrator)),
      static_cast<double>(s.substeps),
      s.slop,
      static_cast<double>(s.position_iterations),
      static_cast<double>(s.velocity_iterations),
      flag(s.warm_starting),
      flag(s.continuous),
      flag(s.shock_propagation),
      flag(s.hold_resting_support),
      s.rest_speed,
      s.max_speed,
      s.max_acceleration,
      flag(s.sleeping),
      s.sleep_speed,
      s.sleep_time,
      flag(s.has_bounds),
      s.bounds.min.x,
      s.bounds.min.y,
      s.bounds.max.x,
      s.bounds.max.y,
      s.max_body_size,
      static_cast<double>(s.max_bodies),
      flag(s.simd_contact_lanes),
      world.dt,
      static_cast<double>(world.bodies.size()),
  };
  out.reserve(kFlatHeader +
              (with_filters ? kFlatBodyFieldsWithFilters : kFlatBodyFields) * world.bodies.size());
  for (const phys::BodyDef& b : world.bodies) {
    const double body[kFlatBodyFields] = {
        b.shape == phys::Shape::Circle ? 0.0 : 1.0,
        b.motion == phys::Motion::Static    ? 0.0
        : b.motion == phys::Motion::Dynamic ? 1.0
                                            : 2.0,
        b.position.x,
        b.position.y,
        b.velocity.x,
        b.velocity.y,
        b.acceleration.x,
        b.acceleration.y,
        b.radius,
        b.half_extents.x,
        b.half_extents.y,
        b.mass,
        b.restitution,
        b.friction.x,
        b.friction.y,
        b.contact_friction,
    };
    out.insert(out.end(), std::begin(body), std::end(body));
    if (with_filters) {
      out.push_back(static_cast<double>(b.filter.category_bits));
      out.push_back(static_cast<double>(b.filter.mask_bits));
      out.push_back(static_cast<double>(b.filter.group));
      out.push_back(flag(b.is_sensor));
    }
  }
  return out;
}

std::variant<FlatWorld, std::string> unflatten(std::span<const double> values) {
  if (values.empty() || (values[0] != kFlatVersion && values[0] != kFlatVersionWithFilters))
    return std::string("value 0 (version) must be 1 or 2");
  const bool with_filters = values[0] == kFlatVersionWithFilters;
  // Version 2's errors say so: its bodies are laid out differently.
  const std::string what = with_filters ? "flat world version 2: " : "flat world: ";
  const std::size_t body_fields = with_filters ? kFlatBodyFieldsWithFilters : kFlatBodyFields;
  if (values.size() < kFlatHeader)
    return "a flat world holds at least " + std::to_string(kFlatHeader) + " values, got " +
           std::to_string(values.size());
  Reader in(values, 1);
  FlatWorld world;
  read_settings(in, world.settings);
  world.dt = in.number("dt");
  const std::int64_t count = in.whole("body count", 0, 1 << 20);
  if (!in.error().empty()) return "flat world: " + in.error();
  if (!(std::isfinite(world.dt) && world.dt > 0.0 && world.dt <= 1.0))
    return std::string("flat world: dt must be a finite number in (0, 1]");
  if (const phys::SettingsError e = phys::check_settings(world.settings);
      e != phys::SettingsError::None)
    return std::string("flat world: settings refused: ") + phys::describe(e);
  const std::size_t expected = kFlatHeader + body_fields * static_cast<std::size_t>(count);
  if (values.size() != expected)
    return what + std::to_string(count) + " bodies take " + std::to_string(expected) +
           " values, got " + std::to_string(values.size());
  world.bodies.reserve(static_cast<std::size_t>(count));
  for (std::int64_t i = 0; i < count; ++i) {
    world.bodies.push_back(read_body(in, with_filters));
    if (!in.error().empty()) return what + "body " + std::to_string(i) + ": " + in.error();
  }
  return world;
}

std::variant<phys::World, std::string> build_world(const FlatWorld& flat) {
  phys::World world(flat.settings);
  for (std::size_t i = 0; i < flat.bodies.size(); ++i) {
    phys::BodyDefError error = phys::BodyDefError::None;
    if (!world.add_body(flat.bodies[i], &error).is_valid())
      return "flat world: body " + std::to_string(i) +
             " refused by the world: " + std::string(phys::describe(error));
  }
  return world;
}

std::string to_json(std::span<const double> values) {
  std::string out = "[";
  char number[40];
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::snprintf(number, sizeof number, "%.17g", values[i]);
    if (i > 0) out += (i % 16 == 12) ? ",\n" : ", ";  // a body a line after the header
    out += number;
  }
  out += "]\n";
  return out;
}

std::variant<std::vector<double>, std::string> from_json(std::string_view text) {
  std::size_t at = 0;
  const auto skip_space = [&] {
    while (at < text.size() &&
           (text[at] == ' ' || text[at] == '\n' || text[at] == '\r' || text[at] == '\t'))
      ++at;
  };
  const auto where = [&] { return "flat world JSON, byte " + std::to_string(at) + ": "; };
  skip_space();
  if (at >= text.size() || text[at] != '[') return where() + "expected '['";
  ++at;
  std::vector<double> values;
  skip_space();
  if (at < text.size() && text[at] == ']') {
    ++at;
  } else {
    for (;;) {
      skip_space();
      // A JSON number: [-] digits [. digits] [e [+-] digits]; no NaN or infinity.
      const std::size_t start = at;
      while (at < text.size() && at - start < 32 &&
             (std::isdigit(static_cast<unsigned char>(text[at])) || text[at] == '-' ||
              text[at] == '+' || text[at] == '.' || text[at] == 'e' || text[at] == 'E'))
        ++at;
      const std::string token(text.substr(start, at - start));
      char* end = nullptr;
      const double value = token.empty() ? 0.0 : std::strtod(token.c_str(), &end);
      if (token.empty() || end != token.c_str() + token.size() || !std::isfinite(value)) {
        at = start;
        return where() + "expected a finite number";
      }
      values.push_back(value);
      skip_space();
      if (at < text.size() && text[at] == ',') {
        ++at;
        continue;
      }
      if (at < text.size() && text[at] == ']') {
        ++at;
        break;
      }
      return where() + "expected ',' or ']'";
    }
  }
  skip_space();
  if (at != text.size()) return where() + "text after the array";
  return values;
}

}  // namespace portable
