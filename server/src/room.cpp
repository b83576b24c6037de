#include "server/room.h"

#include "server/spawn.h"

namespace server {

std::optional<phys::BodyId> Room::join(ClientId client, const scene::SceneDef& scene,
                                       phys::World& world, std::optional<std::uint32_t> seat,
                                       phys::BodyDef* made) {
  if (contains(client)) return std::nullopt;
  const std::optional<phys::Vec2> where = find_spawn_position(scene, world, seat);
  if (!where) return std::nullopt;
  phys::BodyDef def = scene.player;
  def.motion = phys::Motion::Dynamic;
  def.position = *where;
  def.velocity = {};
  def.acceleration = {};
  const phys::BodyId body = world.add_body(def);
  if (!body.is_valid()) return std::nullopt;
  if (made) *made = def;
  bodies_.emplace(client, body);
  return body;
}

std::optional<phys::BodyId> Room::join_as(ClientId client, phys::BodyDef def, phys::World& world,
                                          phys::BodyDef* made) {
  if (contains(client)) return std::nullopt;
  def.motion = phys::Motion::Dynamic;
  const phys::BodyId body = world.add_body(def);
  if (!body.is_valid()) return std::nullopt;
  if (made) *made = def;
  bodies_.emplace(client, body);
  return body;
}

bool Room::leave(ClientId client, phys::World& world) {
  const auto it = bodies_.find(client);
  if (it == bodies_.end()) return false;
  world.remove_body(it->second);
  bodies_.erase(it);
  return true;
}

std::optional<phys::BodyId> Room::body_of(ClientId client) const {
  const auto it = bodies_.find(client);
  if (it == bodies_.end()) return std::nullopt;
  return it->second;
}

}  // namespace server
