// The checker's order: the scene's name, its world, its bodies, its grids, whether
// any bodies overlap, then the player and its spawn points; the first fault ends the
// check.
#include "scene_checker.h"

#include <fmt/format.h>

#include "body_checks.h"
#include "field_checker.h"
#include "field_path.h"
#include "grid_checks.h"
#include "overlap_checks.h"
#include "world_checks.h"

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

bool check_spawns(Checker& check, const proto::Scene& message, SceneDef* def) {
  const FieldPath player_path = FieldPath().child("player");
  def->player = default_player();
  if (message.has_player()) {
    if (!check_body(check, message.player(), player_path, def->world, true, &def->player))
      return false;
    if (message.player().is_static())
      return check.fail(player_path.child("is_static"), "the player's body must be dynamic");
    if (message.player().is_kinematic())
      return check.fail(player_path.child("is_kinematic"), "the player's body must be dynamic");
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
  std::vector<BodySource> sources;
  for (int i = 0; i < message.bodies_size(); ++i) {
    const FieldPath path = FieldPath().child("bodies", i);
    sources.push_back({def.bodies.size(), path, false});
    phys::BodyDef body;
    if (!check_body(check, message.bodies(i), path, def.world, false, &body) ||
        !check_inside(check, path.child("position"), def.world, body, "the body"))
      return check.take_error();
    def.bodies.push_back(body);
  }
  for (int i = 0; i < message.grids_size(); ++i) {
    sources.push_back({def.bodies.size(), FieldPath().child("grids", i), true});
    if (!check_grid(check, message.grids(i), sources.back().path, &def)) return check.take_error();
  }
  if (!check_overlaps(check, def, sources)) return check.take_error();
  if (!check_spawns(check, message, &def)) return check.take_error();
  return def;
}

}  // namespace scene::detail
