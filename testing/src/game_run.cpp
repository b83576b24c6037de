#include "physics_testing/game_run.h"

#include <string>
#include <utility>

namespace physics_testing {

namespace {

std::string describe(server::GameMessageVerdict verdict) {
  switch (verdict) {
    case server::GameMessageVerdict::OnTime:
    case server::GameMessageVerdict::Late:
      return "accepted";
    case server::GameMessageVerdict::TooFarAhead:
      return "its tick is too far ahead";
    case server::GameMessageVerdict::NotJoined:
      return "the client is not in the world";
    case server::GameMessageVerdict::NoGame:
      return "the simulation has no game rules";
    case server::GameMessageVerdict::TooLarge:
      return "it is over " + std::to_string(server::kMaxGameMessageBytes) + " bytes";
    case server::GameMessageVerdict::TooMany:
      return "the client has " + std::to_string(server::kMaxGameMessagesPerTick) +
             " messages at that tick already";
  }
  return "refused";
}

}  // namespace

GameRun::GameRun(scene::SceneDef scene, std::shared_ptr<server::GameRules> rules,
                 server::SimulationOptions options)
    : simulation_(std::move(scene), options, std::move(rules)) {
  simulation_.set_contact_events(true);
}

GameRun::~GameRun() { simulation_.end(); }

Expected<server::ClientId> GameRun::join(std::optional<std::uint32_t> seat) {
  const server::ClientId client = next_client_++;
  const server::Admission admission = simulation_.admit(client, seat);
  if (admission.body) return client;
  if (admission.refused) {
    return Expected<server::ClientId>::failure("the rules refused player " +
                                               std::to_string(client) + ": " + *admission.refused);
  }
  return Expected<server::ClientId>::failure("no free spawn point for player " +
                                             std::to_string(client));
}

Outcome GameRun::leave(server::ClientId client) {
  if (simulation_.leave(client)) return Outcome::success();
  return Outcome::failure("player " + std::to_string(client) + " is not in the world");
}

Outcome GameRun::input(server::ClientId client, double ax, double ay) {
  const server::InputCheck check = simulation_.submit_input(client, tick() + 1, {ax, ay});
  if (check.accepted()) return Outcome::success();
  return Outcome::failure("the input of player " + std::to_string(client) +
                          " was refused (not in the world, or not finite)");
}

Outcome GameRun::message(server::ClientId client, std::string payload) {
  const server::GameMessageVerdict verdict =
      simulation_.submit_game_message(client, tick() + 1, std::move(payload));
  if (verdict == server::GameMessageVerdict::OnTime) return Outcome::success();
  return Outcome::failure("the message of player " + std::to_string(client) +
                          " was refused: " + describe(verdict));
}

Expected<phys::BodyId> GameRun::add_body(const phys::BodyDef& def) {
  phys::BodyDefError error = phys::BodyDefError::None;
  const phys::BodyId id = simulation_.world_handle().create(def, &error);
  if (id.is_valid()) return id;
  return Expected<phys::BodyId>::failure("the world refused the body: " +
                                         std::string(phys::describe(error)));
}

Outcome GameRun::remove_body(phys::BodyId id) {
  if (simulation_.world_handle().destroy(id)) return Outcome::success();
  return Outcome::failure("no body " + std::to_string(id.packed()) +
                          " to remove, or it is a player's (players leave instead)");
}

Outcome GameRun::set_position(phys::BodyId id, double x, double y) {
  if (simulation_.world_handle().set_position(id, {x, y})) return Outcome::success();
  return Outcome::failure("no body " + std::to_string(id.packed()) +
                          " to move there (unknown, static, or a value the world refuses)");
}

Outcome GameRun::set_velocity(phys::BodyId id, double vx, double vy) {
  if (simulation_.world_handle().set_velocity(id, {vx, vy})) return Outcome::success();
  return Outcome::failure("no body " + std::to_string(id.packed()) +
                          " to set moving (unknown, static, or a value the world refuses)");
}

const GameTick& GameRun::step(std::uint64_t ticks) {
  const std::uint64_t count = ticks == 0 ? 1 : ticks;
  for (std::uint64_t i = 0; i < count; ++i) {
    const server::TickResult result = simulation_.step_tick();
    GameTick record;
    record.tick = result.tick;
    record.state_hash = simulation_.world().state_hash();
    record.sensor_events = simulation_.world().sensor_events();
    record.contact_events = simulation_.world().contact_events();
    record.messages = simulation_.take_outgoing_messages();
    history_.push_back(std::move(record));
  }
  return history_.back();
}

std::optional<phys::BodyId> GameRun::find_body(std::string_view name) const {
  return simulation_.world().find_body(name);
}

std::optional<phys::BodyState> GameRun::body(std::string_view name) const {
  const std::optional<phys::BodyId> id = find_body(name);
  if (!id) return std::nullopt;
  return simulation_.world().body(*id);
}

std::optional<phys::BodyId> GameRun::body_of(server::ClientId client) const {
  return simulation_.body_of(client);
}

std::vector<std::string> GameRun::messages_to(server::ClientId client) const {
  std::vector<std::string> payloads;
  for (const GameTick& record : history_) {
    for (const server::OutgoingGameMessage& message : record.messages) {
      if (message.client == client || message.client == 0) payloads.push_back(message.payload);
    }
  }
  return payloads;
}

}  // namespace physics_testing
