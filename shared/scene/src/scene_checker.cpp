#include "scene_checker.h"

#include <fmt/format.h>
#include <google/protobuf/stubs/common.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "field_path.h"

namespace scene::detail {

namespace proto = physics::scene;
using google::protobuf::TextFormat;

namespace {

// The body a client gets when the scene names none.
phys::BodyDef default_player() {
  phys::BodyDef player;
  player.shape = phys::Shape::Circle;
  player.motion = phys::Motion::Dynamic;
  player.radius = 0.5;
  player.mass = 1.0;
  return player;
}

// Records the first fault; every check returns false once one is recorded, so
// callers stop at the first `false`.
class Checker {
 public:
  Checker(std::string_view origin, const TextFormat::ParseInfoTree& locations)
      : origin_(origin), locations_(locations) {}

  bool fail(const FieldPath& path, std::string message) {
    const TextLocation where = path.locate(*proto::Scene::descriptor(), locations_);
    error_ = SceneError{std::string(origin_), where.line, where.column, path.to_string(),
                        std::move(message)};
    return false;
  }
  SceneError take_error() { return std::move(*error_); }

  bool finite(const FieldPath& path, double value) {
    if (std::isfinite(value)) return true;
    return fail(path, fmt::format("must be a finite number, got {}", value));
  }
  bool positive(const FieldPath& path, double value) {
    if (!finite(path, value)) return false;
    if (value > 0.0) return true;
    return fail(path, fmt::format("must be > 0, got {}", value));
  }
  bool not_negative(const FieldPath& path, double value) {
    if (!finite(path, value)) return false;
    if (value >= 0.0) return true;
    return fail(path, fmt::format("must be >= 0, got {}", value));
  }
  bool at_most(const FieldPath& path, double value, double limit, std::string_view why) {
    if (value <= limit) return true;
    return fail(path, fmt::format("must be at most {} ({}), got {}", limit, why, value));
  }
  bool in_range(const FieldPath& path, double value, double low, double high) {
    if (!finite(path, value)) return false;
    if (value >= low && value <= high) return true;
    return fail(path, fmt::format("must be in [{}, {}], got {}", low, high, value));
  }
  bool in_range(const FieldPath& path, std::int64_t value, std::int64_t low, std::int64_t high) {
    if (value >= low && value <= high) return true;
    return fail(path, fmt::format("must be in [{}, {}], got {}", low, high, value));
  }
  bool finite(const FieldPath& path, const proto::Vec2& value) {
    return finite(path.child("x"), value.x()) && finite(path.child("y"), value.y());
  }
  // A position: finite and within kMaxCoordinate of the origin on both axes.
  bool coordinate(const FieldPath& path, const proto::Vec2& value) {
    for (const auto& [axis, number] : {std::pair{"x", value.x()}, std::pair{"y", value.y()}}) {
      const FieldPath axis_path = path.child(axis);
      if (!finite(axis_path, number)) return false;
      if (!at_most(axis_path, std::fabs(number), kMaxCoordinate, "largest |coordinate|"))
        return false;
    }
    return true;
  }

 private:
  std::string_view origin_;
  const TextFormat::ParseInfoTree& locations_;
  std::optional<SceneError> error_;
};

// Names travel to clients in proto3 string fields, which must hold valid UTF-8 (a
// peer refuses the whole message otherwise); short, so that a log line stays one line.
constexpr std::size_t kMaxNameBytes = 256;

bool check_name(Checker& check, const FieldPath& path, const std::string& name) {
  if (name.size() > kMaxNameBytes)
    return check.fail(path,
                      fmt::format("is {} bytes long, more than {}", name.size(), kMaxNameBytes));
  if (!google::protobuf::internal::IsStructurallyValidUTF8(name.data(),
                                                           static_cast<int>(name.size())))
    return check.fail(path, "is not valid UTF-8");
  return true;
}

phys::Vec2 to_vec(const proto::Vec2& value) { return {value.x(), value.y()}; }

phys::Vec2 half_size(const phys::BodyDef& body) {
  return body.shape == phys::Shape::Circle ? phys::Vec2{body.radius, body.radius}
                                           : body.half_extents;
}

// Whether the body's bounding box lies inside the world's bounds (edges included).
bool inside_bounds(const phys::WorldSettings& settings, const phys::BodyDef& body) {
  if (!settings.has_bounds) return true;
  const phys::Vec2 half = half_size(body);
  const phys::Aabb& bounds = settings.bounds;
  return body.position.x - half.x >= bounds.min.x && body.position.x + half.x <= bounds.max.x &&
         body.position.y - half.y >= bounds.min.y && body.position.y + half.y <= bounds.max.y;
}

std::string describe_bounds(const phys::Aabb& bounds) {
  return fmt::format("world.bounds [({}, {}), ({}, {})]", bounds.min.x, bounds.min.y, bounds.max.x,
                     bounds.max.y);
}

bool check_int_setting(Checker& check, const FieldPath& path, bool has, std::int64_t value,
                       std::int64_t low, std::int64_t high, int* out) {
  if (!has) return true;
  if (!check.in_range(path, value, low, high)) return false;
  *out = static_cast<int>(value);
  return true;
}

bool check_world(Checker& check, const proto::World& world, SceneDef* def) {
  const FieldPath base = FieldPath().child("world");
  phys::WorldSettings& settings = def->world;
  if (world.has_gravity()) {
    if (!check.finite(base.child("gravity"), world.gravity())) return false;
    settings.gravity = to_vec(world.gravity());
  }
  if (world.has_tick_rate()) {
    const FieldPath path = base.child("tick_rate");
    if (!check.positive(path, world.tick_rate())) return false;
    if (!check.at_most(path, world.tick_rate(), kMaxTickRate, "ticks per second")) return false;
    def->tick_rate = world.tick_rate();
  }
  if (world.has_steps_per_frame()) {
    if (!check.in_range(base.child("steps_per_frame"), world.steps_per_frame(), 1,
                        kMaxStepsPerFrame))
      return false;
    def->steps_per_frame = static_cast<int>(world.steps_per_frame());
  }
  if (world.has_slop()) {
    if (!check.in_range(base.child("slop"), world.slop(), 0.0, 0.1)) return false;
    settings.slop = world.slop();
  }
  if (world.has_bounds()) {
    const FieldPath path = base.child("bounds");
    const proto::Bounds& bounds = world.bounds();
    if (!check.coordinate(path.child("min"), bounds.min()) ||
        !check.coordinate(path.child("max"), bounds.max()))
      return false;
    if (bounds.max().x() <= bounds.min().x())
      return check.fail(path.child("max").child("x"),
                        fmt::format("must be greater than world.bounds.min.x ({}), got {}",
                                    bounds.min().x(), bounds.max().x()));
    if (bounds.max().y() <= bounds.min().y())
      return check.fail(path.child("max").child("y"),
                        fmt::format("must be greater than world.bounds.min.y ({}), got {}",
                                    bounds.min().y(), bounds.max().y()));
    settings.has_bounds = true;
    settings.bounds = {to_vec(bounds.min()), to_vec(bounds.max())};
  }
  if (world.has_max_acceleration()) {
    const FieldPath path = base.child("max_acceleration");
    if (!check.positive(path, world.max_acceleration())) return false;
    if (!check.at_most(path, world.max_acceleration(), settings.max_acceleration,
                       "the core's acceleration limit"))
      return false;
    def->max_acceleration = world.max_acceleration();
  }
  switch (world.integrator()) {
    case proto::INTEGRATOR_UNSPECIFIED:
      break;
    case proto::INTEGRATOR_EXPLICIT_EULER:
      settings.integrator = phys::Integrator::ExplicitEuler;
      break;
    case proto::INTEGRATOR_SEMI_IMPLICIT_EULER:
      settings.integrator = phys::Integrator::SemiImplicitEuler;
      break;
    case proto::INTEGRATOR_EXACT:
      settings.integrator = phys::Integrator::Exact;
      break;
    default:
      return check.fail(base.child("integrator"),
                        fmt::format("unknown integrator {}", static_cast<int>(world.integrator())));
  }
  if (!check_int_setting(check, base.child("substeps"), world.has_substeps(), world.substeps(), 1,
                         64, &settings.substeps) ||
      !check_int_setting(check, base.child("position_iterations"), world.has_position_iterations(),
                         world.position_iterations(), 1, 64, &settings.position_iterations) ||
      !check_int_setting(check, base.child("velocity_iterations"), world.has_velocity_iterations(),
                         world.velocity_iterations(), 1, 64, &settings.velocity_iterations))
    return false;
  if (world.has_continuous()) settings.continuous = world.continuous();
  if (world.has_sleeping()) settings.sleeping = world.sleeping();
  if (world.has_shock_propagation()) settings.shock_propagation = world.shock_propagation();
  if (world.has_hold_resting_support()) {
    settings.hold_resting_support = world.hold_resting_support();
  }
  if (world.has_rest_speed()) {
    if (!check.not_negative(base.child("rest_speed"), world.rest_speed())) return false;
    settings.rest_speed = world.rest_speed();
  }
  if (world.has_max_speed()) {
    if (!check.positive(base.child("max_speed"), world.max_speed())) return false;
    settings.max_speed = world.max_speed();
  }
  if (world.has_sleep_speed()) {
    if (!check.not_negative(base.child("sleep_speed"), world.sleep_speed())) return false;
    settings.sleep_speed = world.sleep_speed();
  }
  if (world.has_sleep_time()) {
    if (!check.not_negative(base.child("sleep_time"), world.sleep_time())) return false;
    settings.sleep_time = world.sleep_time();
  }
  // The core's own verdict, in case it is stricter than the checks above.
  const phys::SettingsError verdict = phys::check_settings(settings);
  if (verdict == phys::SettingsError::None) return true;
  const char* field = "world";
  switch (verdict) {
    case phys::SettingsError::NonFiniteGravity:
      field = "gravity";
      break;
    case phys::SettingsError::BadSubsteps:
      field = "substeps";
      break;
    case phys::SettingsError::BadSlop:
      field = "slop";
      break;
    case phys::SettingsError::BadIterations:
      field = "position_iterations";
      break;
    case phys::SettingsError::BadSpeedLimit:
      field = "max_speed";
      break;
    case phys::SettingsError::BadSleep:
      field = "sleep_speed";
      break;
    case phys::SettingsError::BadBounds:
      field = "bounds";
      break;
    case phys::SettingsError::None:
      break;
  }
  return check.fail(base.child(field), phys::describe(verdict));
}

// Checks one body (or a grid's or the player's template, whose position must be
// left unset) and converts it.
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
  def.motion = body.is_static() ? phys::Motion::Static : phys::Motion::Dynamic;
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
  *out = def;
  return true;
}

bool check_inside(Checker& check, const FieldPath& path, const phys::WorldSettings& settings,
                  const phys::BodyDef& body, std::string_view what) {
  if (inside_bounds(settings, body)) return true;
  return check.fail(path, fmt::format("{} at ({}, {}) lies outside {}", what, body.position.x,
                                      body.position.y, describe_bounds(settings.bounds)));
}

// How many bodies a grid makes, given counts already known to be in range.
std::int64_t grid_body_count(const proto::Grid& grid) {
  std::int64_t total = 0;
  for (std::int64_t row = 0; row < grid.count_y(); ++row) {
    const std::int64_t in_row = grid.count_x() - row * grid.taper();
    if (in_row <= 0) break;
    total += in_row;
  }
  return total;
}

bool check_grid(Checker& check, const proto::Grid& grid, const FieldPath& path, SceneDef* def) {
  const phys::WorldSettings& settings = def->world;
  if (!grid.has_body()) return check.fail(path.child("body"), "missing: the body the grid repeats");
  phys::BodyDef body;
  if (!check_body(check, grid.body(), path.child("body"), settings, true, &body)) return false;
  if (!check.coordinate(path.child("origin"), grid.origin()) ||
      !check.finite(path.child("spacing"), grid.spacing()))
    return false;
  // Counts are checked one by one before any product is formed, so the total
  // below cannot overflow (at most 2^40) and is known before anything is made.
  if (!check.in_range(path.child("count_x"), grid.count_x(), 1, kMaxSceneBodies) ||
      !check.in_range(path.child("count_y"), grid.count_y(), 1, kMaxSceneBodies) ||
      !check.in_range(path.child("taper"), grid.taper(), 0, grid.count_x()))
    return false;
  const std::int64_t count = grid_body_count(grid);
  const auto already = static_cast<std::int64_t>(def->bodies.size());
  if (count > kMaxSceneBodies - already)
    return check.fail(path, fmt::format("makes {} bodies, and with the {} before it the scene "
                                        "would exceed its limit of {} bodies",
                                        count, already, kMaxSceneBodies));
  def->bodies.reserve(def->bodies.size() + static_cast<std::size_t>(count));
  const phys::Vec2 origin = to_vec(grid.origin());
  const phys::Vec2 spacing = to_vec(grid.spacing());
  for (std::int64_t row = 0; row < grid.count_y(); ++row) {
    const std::int64_t in_row = grid.count_x() - row * grid.taper();
    if (in_row <= 0) break;
    double shift = static_cast<double>(row * grid.taper()) * spacing.x * 0.5;
    if (grid.stagger() && row % 2 == 1) shift += spacing.x * 0.5;
    for (std::int64_t column = 0; column < in_row; ++column) {
      body.position = {origin.x + static_cast<double>(column) * spacing.x + shift,
                       origin.y + static_cast<double>(row) * spacing.y};
      // Formatted only on failure: a grid may place a million bodies.
      auto what = [&] { return fmt::format("body (row {}, column {})", row, column); };
      if (!is_finite(body.position) || std::fabs(body.position.x) > kMaxCoordinate ||
          std::fabs(body.position.y) > kMaxCoordinate)
        return check.fail(
            path, fmt::format("{} at ({}, {}) is beyond the largest |coordinate| {}", what(),
                              body.position.x, body.position.y, kMaxCoordinate));
      if (!inside_bounds(settings, body)) return check_inside(check, path, settings, body, what());
      def->bodies.push_back(body);
    }
  }
  return true;
}

bool check_spawns(Checker& check, const proto::Scene& message, SceneDef* def) {
  const FieldPath player_path = FieldPath().child("player");
  def->player = default_player();
  if (message.has_player()) {
    if (!check_body(check, message.player(), player_path, def->world, true, &def->player))
      return false;
    if (message.player().is_static())
      return check.fail(player_path.child("is_static"), "the player's body must be dynamic");
  }
  if (message.spawn_points_size() == 0)
    return check.fail(FieldPath().child("spawn_points"),
                      "no spawn points: a scene needs at least one, where players join");
  for (int i = 0; i < message.spawn_points_size(); ++i) {
    const FieldPath path = FieldPath().child("spawn_points", i);
    if (!check.coordinate(path, message.spawn_points(i))) return false;
    phys::BodyDef placed = def->player;
    placed.position = to_vec(message.spawn_points(i));
    if (!check_inside(check, path, def->world, placed, "the player's body")) return false;
    def->spawn_points.push_back(placed.position);
  }
  return true;
}

}  // namespace

SceneResult check_scene(const proto::Scene& message, std::string_view origin,
                        const TextFormat::ParseInfoTree& locations) {
  Checker check(origin, locations);
  SceneDef def;
  if (!check_name(check, FieldPath().child("name"), message.name())) return check.take_error();
  def.name = message.name();
  if (!check_world(check, message.world(), &def)) return check.take_error();

  if (message.bodies_size() > kMaxSceneBodies) {
    check.fail(FieldPath().child("bodies"), fmt::format("{} bodies exceed the limit of {}",
                                                        message.bodies_size(), kMaxSceneBodies));
    return check.take_error();
  }
  def.bodies.reserve(static_cast<std::size_t>(message.bodies_size()));
  for (int i = 0; i < message.bodies_size(); ++i) {
    const FieldPath path = FieldPath().child("bodies", i);
    phys::BodyDef body;
    if (!check_body(check, message.bodies(i), path, def.world, false, &body) ||
        !check_inside(check, path.child("position"), def.world, body, "the body"))
      return check.take_error();
    def.bodies.push_back(body);
  }
  for (int i = 0; i < message.grids_size(); ++i) {
    if (!check_grid(check, message.grids(i), FieldPath().child("grids", i), &def))
      return check.take_error();
  }
  if (!check_spawns(check, message, &def)) return check.take_error();
  return def;
}

}  // namespace scene::detail
