// Message dispatch: what each ClientMessage does once its session has read it, the
// Hello aside (server_handshake.cpp).
#include <spdlog/spdlog.h>

#include <chrono>
#include <string>

#include "handshake.h"
#include "log_fields.h"
#include "server_impl.h"
#include "wire/messages.h"

namespace server {

void Server::Impl::on_message(Session& session, physics::wire::ClientMessage& message) {
  using Kind = physics::wire::ClientMessage::KindCase;
  // PROTOCOL.md 3.1: the first message must be Hello. Anything else before it (a
  // Ping included: it must not keep a connection that never joined alive) is fatal;
  // Bye closes quietly, and an empty envelope is malformed (below).
  const Kind kind = message.kind_case();
  if (!session.joined() && kind != Kind::kHello && kind != Kind::kBye &&
      kind != Kind::KIND_NOT_SET) {
    session.close_with_error(physics::wire::ERROR_UNEXPECTED_MESSAGE,
                             "a message before Hello: the first message must be Hello",
                             DropReason::UnexpectedMessage);
    return;
  }
  switch (kind) {
    case Kind::kHello:
      on_hello(session, message.hello());
      return;
    case Kind::kInput:
      if (handshake_.is_spectator(session.id())) {
        session.send(wire::make_error(physics::wire::ERROR_SPECTATOR_INPUT,
                                      "a spectator has no body to move; input dropped", false));
        return;
      }
      on_input(session, message.input());
      return;
    case Kind::kGameMessage:
      on_game_message(session, message.game_message());
      return;
    case Kind::kPing: {
      physics::wire::ServerMessage reply;
      physics::wire::Pong& pong = *reply.mutable_pong();
      pong.set_nonce(message.ping().nonce());
      pong.set_client_time_ns(message.ping().client_time_ns());
      pong.set_server_tick(simulation_.current_tick());
      session.send(reply);
      return;
    }
    case Kind::kAck:
      on_ack(session, message.ack());
      return;
    case Kind::kFullStateRequest:
      on_full_state_request(session);
      return;
    case Kind::kBye:
      if (log_admits("bye", session.address())) {
        log_with(spdlog::level::info,
                 {.client = session.id(),
                  .address = session.peer(),
                  .reason = to_string(DropReason::ClientBye)},
                 "client {} says bye: {}", session.id(), printable_name(message.bye().reason()));
      }
      session.close_when_written(DropReason::ClientBye);
      return;
    case Kind::KIND_NOT_SET:
      break;
  }
  session.close_with_error(physics::wire::ERROR_MALFORMED,
                           "ClientMessage holds no known message (empty or from a newer "
                           "protocol)",
                           DropReason::Malformed);
}

void Server::Impl::on_ack(Session& session, const physics::wire::Ack& ack) {
  // Only an Ack that takes snapshots off the window proves the client reads: the
  // same old Ack again does not.
  const std::size_t before = feeds_.unacknowledged(session.id());
  if (feeds_.ack(session.id(), ack.tick(), clock_.now()) == AckResult::Accepted) {
    if (feeds_.unacknowledged(session.id()) < before) {
      session.note_read_proof(std::chrono::steady_clock::now());
    }
    return;
  }
  update_stats([](ServerStats& s) { ++s.invalid_acks; });
  session.send(wire::make_error(physics::wire::ERROR_INVALID_ACK,
                                "Ack for tick " + std::to_string(ack.tick()) +
                                    ", after the newest snapshot sent to this client; ignored",
                                false));
}

void Server::Impl::on_full_state_request(Session& session) {
  // Each full state costs the whole world's bytes: counted against the client's
  // budget, so that asking again and again cannot multiply what it is sent.
  if (const auto wait = session.full_state_wait(std::chrono::steady_clock::now());
      wait.count() > 0) {
    update_stats([](ServerStats& s) { ++s.rate_limited; });
    session.send(wire::make_error(
        physics::wire::ERROR_RATE_LIMITED,
        "full states over this client's budget of " +
            std::to_string(static_cast<long long>(config_.full_state_bytes_per_second)) +
            " bytes a second; ask again in " +
            std::to_string(std::chrono::ceil<std::chrono::milliseconds>(wait).count()) + " ms",
        false));
    return;
  }
  if (feeds_.request_full_state(session.id()) == FullStateResult::Accepted) {
    if (const auto relay = relay_cursors_.find(session.id()); relay != relay_cursors_.end()) {
      relay->second.resync = true;
    }
    return;
  }
  update_stats([](ServerStats& s) { ++s.rate_limited; });
  session.send(wire::make_error(physics::wire::ERROR_RATE_LIMITED,
                                "a full state is already on its way to this client; the "
                                "request is merged with it",
                                false));
}

void Server::Impl::on_input(Session& session, const physics::wire::Input& input) {
  const InputCheck check =
      simulation_.submit_input(session.id(), input.tick(), {input.ax(), input.ay()});
  switch (check.verdict) {
    case InputVerdict::NonFinite:
      update_stats([](ServerStats& s) { ++s.invalid_inputs; });
      session.send(wire::make_error(physics::wire::ERROR_INVALID_INPUT,
                                    "input for tick " + std::to_string(input.tick()) +
                                        " has a NaN or infinite acceleration; dropped",
                                    false));
      return;
    case InputVerdict::TooFarAhead:
      update_stats([](ServerStats& s) { ++s.far_future_inputs; });
      session.send(wire::make_error(
          physics::wire::ERROR_TICK_TOO_FAR_AHEAD,
          "input for tick " + std::to_string(input.tick()) + " is more than " +
              std::to_string(simulation_.max_ticks_ahead()) + " ticks after the current tick " +
              std::to_string(simulation_.current_tick()) + "; dropped",
          false));
      return;
    case InputVerdict::NotJoined:
      return;  // cannot happen: on_message only passes inputs of joined sessions
    case InputVerdict::Late:
      update_stats([](ServerStats& s) { ++s.late_inputs; });
      break;
    case InputVerdict::OnTime:
      break;
  }
  input_timing_.arrived(session.id(), input.tick(), clock_.now());
  if (check.clamped) {
    update_stats([](ServerStats& s) { ++s.clamped_inputs; });
    // Said once a player, not once an input: a client that always pushes past the
    // limit learns it without being sent an Error per tick.
    if (told_clamped_.insert(session.id()).second) {
      session.send(
          wire::make_error(physics::wire::ERROR_INPUT_CLAMPED,
                           "input for tick " + std::to_string(input.tick()) +
                               " is over the scene's max acceleration " +
                               std::to_string(simulation_.scene().max_acceleration) +
                               " m/s^2 (Welcome.max_acceleration) and was clamped to it; said once",
                           false));
    }
  }
  if (config_.lockstep) schedule_lockstep();
}

void Server::Impl::on_game_message(Session& session, const physics::wire::GameMessage& message) {
  const GameMessageVerdict verdict =
      simulation_.submit_game_message(session.id(), message.tick(), message.payload());
  const auto refuse = [&](physics::wire::ErrorCode code, const std::string& why) {
    update_stats([](ServerStats& s) { ++s.game_messages_refused; });
    session.send(wire::make_error(code, why + "; game message dropped", false));
  };
  switch (verdict) {
    case GameMessageVerdict::OnTime:
    case GameMessageVerdict::Late:
      update_stats([](ServerStats& s) { ++s.game_messages; });
      return;
    case GameMessageVerdict::TooFarAhead:
      return refuse(physics::wire::ERROR_TICK_TOO_FAR_AHEAD,
                    "game message for tick " + std::to_string(message.tick()) + ", more than " +
                        std::to_string(simulation_.max_ticks_ahead()) + " ticks ahead of " +
                        std::to_string(simulation_.current_tick()));
    case GameMessageVerdict::NotJoined:
      return refuse(physics::wire::ERROR_INVALID_GAME_MESSAGE,
                    "game message from a client without a body in the world");
    case GameMessageVerdict::NoGame:
      return refuse(physics::wire::ERROR_INVALID_GAME_MESSAGE,
                    "this server runs no game: game messages have nowhere to go");
    case GameMessageVerdict::TooLarge:
      return refuse(physics::wire::ERROR_INVALID_GAME_MESSAGE,
                    "game message of " + std::to_string(message.payload().size()) +
                        " bytes, over the limit of " + std::to_string(kMaxGameMessageBytes));
    case GameMessageVerdict::TooMany:
      return refuse(physics::wire::ERROR_INVALID_GAME_MESSAGE,
                    "more than " + std::to_string(kMaxGameMessagesPerTick) +
                        " game messages for tick " + std::to_string(message.tick()));
  }
}

void Server::Impl::send_game_messages() {
  for (OutgoingGameMessage& out : simulation_.take_outgoing_messages()) {
    physics::wire::ServerMessage message;
    message.mutable_game_message()->set_tick(out.tick);
    message.mutable_game_message()->set_payload(std::move(out.payload));
    if (out.client != 0) {
      const auto it = sessions_.find(out.client);
      if (it != sessions_.end() && it->second->joined()) it->second->send(message);
      continue;
    }
    for (const auto& [id, session] : sessions_) {
      if (session->joined()) session->send(message);
    }
  }
}

}  // namespace server
