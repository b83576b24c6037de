#pragma once
// Who is in the world and which body each client owns. The room is the only place
// that maps a client to a body, so a client can only ever reach its own body.
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "physics/body.h"
#include "physics/world.h"
#include "scene/scene.h"

namespace server {

using ClientId = std::uint32_t;

class Room {
 public:
  // Adds the client's body (the scene's player template at a free spawn position).
  // nullopt when the client is already in, or no spawn position is free.
  // `seat`: see find_spawn_position.
  // `made`, when given, receives the definition the body was added with.
  std::optional<phys::BodyId> join(ClientId client, const scene::SceneDef& scene,
                                   phys::World& world,
                                   std::optional<std::uint32_t> seat = std::nullopt,
                                   phys::BodyDef* made = nullptr);
  // Adds the client's body as `def` says (game rules chose it; its motion made
  // dynamic). nullopt when the client is already in or the world refuses the def.
  std::optional<phys::BodyId> join_as(ClientId client, phys::BodyDef def, phys::World& world,
                                      phys::BodyDef* made = nullptr);
  // Removes the client's body; false when the client was not in the room.
  bool leave(ClientId client, phys::World& world);

  std::optional<phys::BodyId> body_of(ClientId client) const;
  bool contains(ClientId client) const { return bodies_.count(client) != 0; }
  std::size_t size() const { return bodies_.size(); }
  // Clients in ascending id order (the order inputs are applied in).
  const std::map<ClientId, phys::BodyId>& members() const { return bodies_; }

 private:
  std::map<ClientId, phys::BodyId> bodies_;
};

}  // namespace server
