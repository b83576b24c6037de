// Carrying out a Hello's decision (handshake.h decides): the fatal Error, or the
// session marked joined and registered with the feeds, and its Welcome; the lockstep
// lobby's Welcomes once every seat is taken.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <utility>
#include <vector>

#include "handshake.h"
#include "log_fields.h"
#include "server_impl.h"
#include "snapshot_encoder.h"
#include "wire/view_settings.h"

namespace server {

void Server::Impl::on_hello(Session& session, const physics::wire::Hello& hello) {
  session.set_wants_world(hello.want_world());
  session.set_runs_rules(hello.run_rules());
  // An address whose players were dropped for straggling or not reading waits
  // before it takes a seat again (address_limits.h).
  if (!session.joined() && !hello.spectate()) {
    const auto wait =
        address_limits_.seat_wait(session.address(), std::chrono::steady_clock::now());
    if (wait.count() > 0) {
      session.close_with_error(
          physics::wire::ERROR_RATE_LIMITED,
          "a player from " + session.address() +
              " was dropped for straggling or not reading; take a seat again in " +
              std::to_string(std::chrono::ceil<std::chrono::milliseconds>(wait).count()) + " ms",
          DropReason::SeatBackoff);
      return;
    }
  }
  // The wall clock, which connect tickets expire by, is read here, never in the tick.
  const auto now = std::chrono::duration_cast<std::chrono::seconds>(
      std::chrono::system_clock::now().time_since_epoch());
  HelloDecision decision =
      handshake_.decide(session.id(), session.joined(), hello, simulation_, session.address(),
                        static_cast<std::uint64_t>(std::max<std::int64_t>(0, now.count())));
  // Held from its check on, whatever follows; on_closed forgets it.
  if (decision.contacts) feeds_.subscribe_contacts(session.id(), std::move(*decision.contacts));
  if (decision.sensor_events) feeds_.subscribe_sensor_events(session.id());
  switch (decision.outcome) {
    case HelloDecision::Outcome::Refused:
      session.close_with_error(decision.refusal.code, decision.refusal.text,
                               decision.refusal.reason);
      return;
    case HelloDecision::Outcome::Spectator:
      session.set_joined(decision.name);
      address_limits_.on_joined(session.address());
      welcome_spectator(session, decision.view);
      return;
    case HelloDecision::Outcome::Lobby:
      // Seated now, welcomed (with a body) once every seat is taken.
      session.set_joined(decision.name);
      address_limits_.on_joined(session.address());
      publish_connection_counts();
      if (log_admits("joined", session.address())) {
        log_with(spdlog::level::info, {.client = session.id(), .address = session.peer()},
                 "client {} '{}' ({}) seated in the lobby at seat {} ({} of {})", session.id(),
                 session.name(), session.peer(), decision.seat, handshake_.seats().taken(),
                 handshake_.seats().size());
      }
      if (decision.lobby_full) open_lobby();
      return;
    case HelloDecision::Outcome::Player:
      session.set_joined(decision.name);
      address_limits_.on_joined(session.address());
      welcome_player(session, decision.body, decision.view);
      return;
  }
}

void Server::Impl::welcome_player(Session& session, phys::BodyId body,
                                  const wire::ViewSettings& view) {
  feeds_.join(session.id(), view, body.packed());
  publish_connection_counts();
  const std::uint32_t seat = handshake_.seats().seat_of(session.id()).value_or(0);
  if (log_admits("joined", session.address())) {
    log_with(
        spdlog::level::info,
        {.client = session.id(), .address = session.peer(), .tick = simulation_.current_tick()},
        "client {} '{}' ({}) joined at tick {} in seat {} with body {}", session.id(),
        session.name(), session.peer(), simulation_.current_tick(), seat, body.packed());
  }
  physics::wire::ServerMessage welcome =
      make_welcome(simulation_, session.id(), body, config_.lockstep, wire::to_wire(view),
                   static_cast<std::uint32_t>(config_.max_clients));
  welcome.mutable_welcome()->set_seat(seat);
  welcome.mutable_welcome()->set_seats(handshake_.seats().size());
  give_world(session, view, welcome);
  session.send(welcome);
}

void Server::Impl::give_world(Session& session, const wire::ViewSettings& view,
                              physics::wire::ServerMessage& welcome) {
  if (!session.wants_world()) return;
  const std::vector<std::uint8_t> bytes = simulation_.world().to_bytes();
  welcome.mutable_welcome()->set_world_state(bytes.data(), bytes.size());
  write_players(simulation_, *welcome.mutable_welcome()->mutable_players());
  if (view.encoding == physics::wire::ENCODING_INPUTS) {
    // The relay is attached only while a welcomed client follows it: the Simulation
    // pays a state hash per tick for it, and the log only holds what such clients need.
    if (relay_cursors_.empty()) simulation_.relay_to(&relay_log_);
    // A client that runs the rules is sent their inputs and messages, not their changes.
    const bool runs_rules = session.runs_rules() && simulation_.has_rules();
    welcome.mutable_welcome()->set_rules_run_here(runs_rules);
    relay_cursors_[session.id()] = {
        simulation_.current_tick(), relay_log_.next_change(), false,
        runs_rules ? RelayLog::Audience::RulesRunners : RelayLog::Audience::Followers};
    update_stats([&](ServerStats& s) { s.relay_clients = relay_cursors_.size(); });
  }
}

void Server::Impl::forget_relay_client(ClientId client) {
  if (relay_cursors_.erase(client) == 0) return;
  if (relay_cursors_.empty()) {
    simulation_.relay_to(nullptr);
    // Ticks logged before the gap would not be consecutive with the ticks after it.
    relay_log_ = RelayLog{};
  }
  update_stats([&](ServerStats& s) { s.relay_clients = relay_cursors_.size(); });
}

// Every seat is taken: the handshake makes the bodies in seat order; every player
// is then welcomed at tick 0.
void Server::Impl::open_lobby() {
  const LobbyOpening opening = handshake_.open_lobby(simulation_);
  for (const ClientId id : opening.no_spawn) {
    if (const auto session = sessions_.find(id); session != sessions_.end()) {
      session->second->close_with_error(physics::wire::ERROR_NO_SPAWN,
                                        "no free spawn position for another body",
                                        DropReason::NoSpawn);
    }
  }
  for (const auto& [id, why] : opening.refused) {
    if (const auto session = sessions_.find(id); session != sessions_.end()) {
      session->second->close_with_error(physics::wire::ERROR_REFUSED_BY_GAME,
                                        "refused by the game: " + why, DropReason::RefusedByGame);
    }
  }
  std::size_t welcomed = 0;
  for (const LobbyWelcome& player : opening.welcomed) {
    const auto session = sessions_.find(player.client);
    if (session == sessions_.end()) continue;  // on_closed leaves the lobby first
    const std::shared_ptr<Session> held = session->second;
    welcome_player(*held, player.body, player.view);
    ++welcomed;
  }
  update_stats([](ServerStats& s) { s.lockstep_started = true; });
  spdlog::info("lobby full: {} players welcomed, tick 1 waits for their inputs", welcomed);
}

void Server::Impl::welcome_spectator(Session& session, const wire::ViewSettings& view) {
  feeds_.join(session.id(), view, std::nullopt);
  publish_connection_counts();
  if (log_admits("joined", session.address())) {
    log_with(
        spdlog::level::info,
        {.client = session.id(), .address = session.peer(), .tick = simulation_.current_tick()},
        "spectator {} '{}' ({}) joined at tick {}", session.id(), session.name(), session.peer(),
        simulation_.current_tick());
  }
  physics::wire::ServerMessage welcome =
      make_welcome(simulation_, session.id(), phys::BodyId::invalid(), config_.lockstep,
                   wire::to_wire(view), static_cast<std::uint32_t>(config_.max_clients));
  welcome.mutable_welcome()->set_body_id(0);
  welcome.mutable_welcome()->set_spectator(true);
  give_world(session, view, welcome);
  session.send(welcome);
}

}  // namespace server
