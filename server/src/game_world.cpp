// The game rules' handle on the world (game_rules.h): each change made on the
// host's world and reported to the host (the server passes it on to snapshots and
// the relay).
#include "server/game_rules.h"

namespace server {

std::uint64_t GameWorld::tick() const { return host_.rules_tick(); }
double GameWorld::dt() const { return host_.rules_dt(); }

phys::BodyId GameWorld::create(const phys::BodyDef& def, phys::BodyDefError* error) {
  const phys::BodyId id = host_.rules_world().add_body(def, error);
  if (id.is_valid()) host_.rules_added(id, def);
  return id;
}

bool GameWorld::destroy(phys::BodyId id) {
  for (const auto& [client, body] : host_.rules_players()) {
    if (body == id) return false;  // a player's body leaves with its player
  }
  if (!host_.rules_world().remove_body(id)) return false;
  host_.rules_removed(id);
  return true;
}

bool GameWorld::set_position(phys::BodyId id, phys::Vec2 position) {
  if (!host_.rules_world().set_position(id, position)) return false;
  host_.rules_set(id, position, std::nullopt, std::nullopt);
  return true;
}

bool GameWorld::set_velocity(phys::BodyId id, phys::Vec2 velocity) {
  if (!host_.rules_world().set_velocity(id, velocity)) return false;
  host_.rules_set(id, std::nullopt, velocity, std::nullopt);
  return true;
}

bool GameWorld::set_acceleration(phys::BodyId id, phys::Vec2 acceleration) {
  if (!host_.rules_world().set_acceleration(id, acceleration)) return false;
  host_.rules_set(id, std::nullopt, std::nullopt, acceleration);
  return true;
}

bool GameWorld::apply_impulse(phys::BodyId id, phys::Vec2 impulse) {
  const std::optional<phys::BodyState> body = host_.rules_world().body(id);
  if (!body || body->motion != phys::Motion::Dynamic || !(body->mass > 0.0)) return false;
  return set_velocity(
      id, {body->velocity.x + impulse.x / body->mass, body->velocity.y + impulse.y / body->mass});
}

std::optional<phys::BodyState> GameWorld::body(phys::BodyId id) const {
  return host_.rules_world().body(id);
}
std::vector<phys::BodyState> GameWorld::bodies() const { return host_.rules_world().bodies(); }
std::size_t GameWorld::body_count() const { return host_.rules_world().body_count(); }
std::optional<phys::BodyId> GameWorld::body_of(ClientId client) const {
  const auto& players = host_.rules_players();
  const auto it = players.find(client);
  if (it == players.end()) return std::nullopt;
  return it->second;
}
const std::map<ClientId, phys::BodyId>& GameWorld::players() const { return host_.rules_players(); }
const std::vector<phys::ContactEvent>& GameWorld::contact_events() const {
  return host_.rules_world().contact_events();
}
const std::vector<phys::SensorEvent>& GameWorld::sensor_events() const {
  return host_.rules_world().sensor_events();
}
const std::vector<phys::CrushEvent>& GameWorld::crush_events() const {
  return host_.rules_world().crush_events();
}
std::optional<phys::BodyId> GameWorld::find_body(std::string_view name) const {
  return host_.rules_world().find_body(name);
}
std::uint64_t GameWorld::state_hash() const { return host_.rules_world().state_hash(); }

// ---- Queries (physics/query.h), answered by the world as it is ----

std::optional<phys::CastHit> GameWorld::cast_ray(phys::Vec2 origin, phys::Vec2 translation,
                                                 const phys::QueryFilter& filter,
                                                 phys::QueryError* error) const {
  return host_.rules_world().cast_ray(origin, translation, filter, error);
}
std::vector<phys::CastHit> GameWorld::cast_ray_all(phys::Vec2 origin, phys::Vec2 translation,
                                                   const phys::QueryFilter& filter,
                                                   phys::QueryError* error) const {
  return host_.rules_world().cast_ray_all(origin, translation, filter, error);
}
std::vector<phys::BodyId> GameWorld::overlap_box(const phys::Aabb& box,
                                                 const phys::QueryFilter& filter,
                                                 phys::QueryError* error) const {
  return host_.rules_world().overlap_box(box, filter, error);
}
std::vector<phys::BodyId> GameWorld::overlap_circle(phys::Vec2 center, double radius,
                                                    const phys::QueryFilter& filter,
                                                    phys::QueryError* error) const {
  return host_.rules_world().overlap_circle(center, radius, filter, error);
}
std::vector<phys::BodyId> GameWorld::overlap_point(phys::Vec2 point,
                                                   const phys::QueryFilter& filter,
                                                   phys::QueryError* error) const {
  return host_.rules_world().overlap_point(point, filter, error);
}
std::optional<phys::CastHit> GameWorld::cast_circle(phys::Vec2 center, double radius,
                                                    phys::Vec2 translation,
                                                    const phys::QueryFilter& filter,
                                                    phys::QueryError* error) const {
  return host_.rules_world().cast_circle(center, radius, translation, filter, error);
}
std::optional<phys::CastHit> GameWorld::cast_box(phys::Vec2 center, phys::Vec2 half_extents,
                                                 phys::Vec2 translation,
                                                 const phys::QueryFilter& filter,
                                                 phys::QueryError* error) const {
  return host_.rules_world().cast_box(center, half_extents, translation, filter, error);
}

// ---- The game state (phys::GameState in the world) ----

namespace {
bool answer(phys::GameStateError result, phys::GameStateError* error) {
  if (error) *error = result;
  return result == phys::GameStateError::None;
}
}  // namespace

std::int64_t GameWorld::get_int(std::string_view name, std::uint64_t index,
                                std::int64_t fallback) const {
  return game_state().get_int(name, index).value_or(fallback);
}
double GameWorld::get_number(std::string_view name, std::uint64_t index, double fallback) const {
  return game_state().get_number(name, index).value_or(fallback);
}
bool GameWorld::set_int(std::string_view name, std::int64_t value, std::uint64_t index,
                        phys::GameStateError* error) {
  return answer(host_.rules_world().game_state().set_int(name, index, value), error);
}
bool GameWorld::set_number(std::string_view name, double value, std::uint64_t index,
                           phys::GameStateError* error) {
  return answer(host_.rules_world().game_state().set_number(name, index, value), error);
}
bool GameWorld::erase(std::string_view name, std::uint64_t index) {
  phys::GameState& state = host_.rules_world().game_state();
  const bool had_int = state.erase_int(name, index);
  const bool had_number = state.erase_number(name, index);
  return had_int || had_number;
}
bool GameWorld::start_timer(std::string_view name, std::uint64_t after_ticks,
                            std::uint64_t every_ticks, std::uint64_t index,
                            phys::GameStateError* error) {
  const std::uint64_t now = host_.rules_tick();
  // A delay that would run past the last tick is refused as a delay of none is.
  const std::uint64_t due = after_ticks > UINT64_MAX - now ? now : now + after_ticks;
  return answer(host_.rules_world().game_state().start_timer(name, index, now, due, every_ticks),
                error);
}
bool GameWorld::cancel_timer(std::string_view name, std::uint64_t index) {
  return host_.rules_world().game_state().cancel_timer(name, index);
}
const phys::GameState& GameWorld::game_state() const { return host_.rules_world().game_state(); }

const std::vector<ClientGameMessage>& GameWorld::messages() const { return host_.rules_messages(); }

bool GameWorld::send(ClientId client, std::string payload) {
  if (payload.size() > kMaxOutgoingGameMessageBytes) return false;
  host_.rules_send({client, host_.rules_tick(), std::move(payload)});
  return true;
}

bool GameWorld::broadcast(std::string payload) { return send(0, std::move(payload)); }

}  // namespace server
