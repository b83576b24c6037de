// The game rules' handle on the world (game_rules.h): each change made on the
// Simulation's world and reported as any change is, to snapshots and the relay.
#include "server/game_rules.h"
#include "server/relay_log.h"
#include "server/simulation.h"

namespace server {

std::uint64_t GameWorld::tick() const { return simulation_.rules_tick_; }
double GameWorld::dt() const { return simulation_.dt_; }

phys::BodyId GameWorld::create(const phys::BodyDef& def, phys::BodyDefError* error) {
  const phys::BodyId id = simulation_.world_.add_body(def, error);
  if (id.is_valid()) simulation_.note_added(id, def);
  return id;
}

bool GameWorld::destroy(phys::BodyId id) {
  for (const auto& [client, body] : simulation_.room_.members()) {
    if (body == id) return false;  // a player's body leaves with its player
  }
  if (!simulation_.world_.remove_body(id)) return false;
  simulation_.note_removed(id);
  return true;
}

bool GameWorld::set_position(phys::BodyId id, phys::Vec2 position) {
  if (!simulation_.world_.set_position(id, position)) return false;
  if (simulation_.relay_) simulation_.relay_->set(id, position, std::nullopt, std::nullopt);
  return true;
}

bool GameWorld::set_velocity(phys::BodyId id, phys::Vec2 velocity) {
  if (!simulation_.world_.set_velocity(id, velocity)) return false;
  if (simulation_.relay_) simulation_.relay_->set(id, std::nullopt, velocity, std::nullopt);
  return true;
}

bool GameWorld::set_acceleration(phys::BodyId id, phys::Vec2 acceleration) {
  if (!simulation_.world_.set_acceleration(id, acceleration)) return false;
  if (simulation_.relay_) simulation_.relay_->set(id, std::nullopt, std::nullopt, acceleration);
  return true;
}

bool GameWorld::apply_impulse(phys::BodyId id, phys::Vec2 impulse) {
  const std::optional<phys::BodyState> body = simulation_.world_.body(id);
  if (!body || body->motion != phys::Motion::Dynamic || !(body->mass > 0.0)) return false;
  return set_velocity(
      id, {body->velocity.x + impulse.x / body->mass, body->velocity.y + impulse.y / body->mass});
}

std::optional<phys::BodyState> GameWorld::body(phys::BodyId id) const {
  return simulation_.world_.body(id);
}
std::vector<phys::BodyState> GameWorld::bodies() const { return simulation_.world_.bodies(); }
std::size_t GameWorld::body_count() const { return simulation_.world_.body_count(); }
std::optional<phys::BodyId> GameWorld::body_of(ClientId client) const {
  return simulation_.room_.body_of(client);
}
const std::map<ClientId, phys::BodyId>& GameWorld::players() const {
  return simulation_.room_.members();
}
const std::vector<phys::ContactEvent>& GameWorld::contact_events() const {
  return simulation_.world_.contact_events();
}
const std::vector<phys::SensorEvent>& GameWorld::sensor_events() const {
  return simulation_.world_.sensor_events();
}
const std::vector<phys::CrushEvent>& GameWorld::crush_events() const {
  return simulation_.world_.crush_events();
}
std::optional<phys::BodyId> GameWorld::find_body(std::string_view name) const {
  return simulation_.world_.find_body(name);
}
std::uint64_t GameWorld::state_hash() const { return simulation_.world_.state_hash(); }

// ---- Queries (physics/query.h), answered by the world as it is ----

std::optional<phys::CastHit> GameWorld::cast_ray(phys::Vec2 origin, phys::Vec2 translation,
                                                 const phys::QueryFilter& filter,
                                                 phys::QueryError* error) const {
  return simulation_.world_.cast_ray(origin, translation, filter, error);
}
std::vector<phys::CastHit> GameWorld::cast_ray_all(phys::Vec2 origin, phys::Vec2 translation,
                                                   const phys::QueryFilter& filter,
                                                   phys::QueryError* error) const {
  return simulation_.world_.cast_ray_all(origin, translation, filter, error);
}
std::vector<phys::BodyId> GameWorld::overlap_box(const phys::Aabb& box,
                                                 const phys::QueryFilter& filter,
                                                 phys::QueryError* error) const {
  return simulation_.world_.overlap_box(box, filter, error);
}
std::vector<phys::BodyId> GameWorld::overlap_circle(phys::Vec2 center, double radius,
                                                    const phys::QueryFilter& filter,
                                                    phys::QueryError* error) const {
  return simulation_.world_.overlap_circle(center, radius, filter, error);
}
std::vector<phys::BodyId> GameWorld::overlap_point(phys::Vec2 point,
                                                   const phys::QueryFilter& filter,
                                                   phys::QueryError* error) const {
  return simulation_.world_.overlap_point(point, filter, error);
}
std::optional<phys::CastHit> GameWorld::cast_circle(phys::Vec2 center, double radius,
                                                    phys::Vec2 translation,
                                                    const phys::QueryFilter& filter,
                                                    phys::QueryError* error) const {
  return simulation_.world_.cast_circle(center, radius, translation, filter, error);
}
std::optional<phys::CastHit> GameWorld::cast_box(phys::Vec2 center, phys::Vec2 half_extents,
                                                 phys::Vec2 translation,
                                                 const phys::QueryFilter& filter,
                                                 phys::QueryError* error) const {
  return simulation_.world_.cast_box(center, half_extents, translation, filter, error);
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
  return answer(simulation_.world_.game_state().set_int(name, index, value), error);
}
bool GameWorld::set_number(std::string_view name, double value, std::uint64_t index,
                           phys::GameStateError* error) {
  return answer(simulation_.world_.game_state().set_number(name, index, value), error);
}
bool GameWorld::erase(std::string_view name, std::uint64_t index) {
  phys::GameState& state = simulation_.world_.game_state();
  const bool had_int = state.erase_int(name, index);
  const bool had_number = state.erase_number(name, index);
  return had_int || had_number;
}
bool GameWorld::start_timer(std::string_view name, std::uint64_t after_ticks,
                            std::uint64_t every_ticks, std::uint64_t index,
                            phys::GameStateError* error) {
  const std::uint64_t now = simulation_.rules_tick_;
  // A delay that would run past the last tick is refused as a delay of none is.
  const std::uint64_t due = after_ticks > UINT64_MAX - now ? now : now + after_ticks;
  return answer(simulation_.world_.game_state().start_timer(name, index, now, due, every_ticks),
                error);
}
bool GameWorld::cancel_timer(std::string_view name, std::uint64_t index) {
  return simulation_.world_.game_state().cancel_timer(name, index);
}
const phys::GameState& GameWorld::game_state() const { return simulation_.world_.game_state(); }

const std::vector<ClientGameMessage>& GameWorld::messages() const {
  return simulation_.delivering_;
}

bool GameWorld::send(ClientId client, std::string payload) {
  if (payload.size() > kMaxOutgoingGameMessageBytes) return false;
  simulation_.outgoing_.push_back({client, simulation_.rules_tick_, std::move(payload)});
  return true;
}

bool GameWorld::broadcast(std::string payload) { return send(0, std::move(payload)); }

}  // namespace server
