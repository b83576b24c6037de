// The Hello checks, in docs/PROTOCOL.md 3.1's order, and who is in: seats, the
// lockstep lobby, the spectators.
#include "handshake.h"

#include <algorithm>
#include <utility>

#include "wire/messages.h"

namespace server {
namespace {

HelloDecision refuse(HelloDecision decision, physics::wire::ErrorCode code, std::string text,
                     DropReason reason) {
  decision.outcome = HelloDecision::Outcome::Refused;
  decision.refusal = {code, std::move(text), reason};
  return decision;
}

}  // namespace

std::string printable_name(const std::string& raw) {
  std::string name = raw.substr(0, kMaxClientNameBytes);
  for (char& c : name) {
    if (c < 0x20 || c == 0x7F) c = '?';
  }
  return name;
}

bool same_token(const std::string& given, const std::string& expected) {
  unsigned char difference = given.size() == expected.size() ? 0 : 1;
  for (std::size_t i = 0; i < given.size(); ++i) {
    difference |= static_cast<unsigned char>(given[i] ^ expected[i % (expected.size() + 1)]);
  }
  return difference == 0;
}

bool is_failed_hello(DropReason reason) {
  switch (reason) {
    case DropReason::MessageTooLarge:
    case DropReason::Malformed:
    case DropReason::ProtocolVersion:
    case DropReason::BadToken:
    case DropReason::UnexpectedMessage:
    case DropReason::InvalidView:
    case DropReason::InvalidSubscription:
    case DropReason::HandshakeTimeout:
      return true;
    default:
      return false;
  }
}

Handshake::Handshake(const ServerConfig& config)
    : token_(config.token),
      tickets_(config.ticket_key, config.ticket_room, config.lockstep_players > 0),
      max_clients_(static_cast<std::size_t>(config.max_clients)),
      max_spectators_(static_cast<std::size_t>(config.max_spectators)),
      max_snapshot_window_(config.max_snapshot_window),
      seats_(static_cast<std::uint32_t>(config.lockstep_players > 0 ? config.lockstep_players
                                                                    : config.max_clients)),
      lobby_open_(config.lockstep_players == 0),
      max_players_per_address_(
          static_cast<std::size_t>(std::max(0, config.max_players_per_address))) {}

HelloDecision Handshake::decide(ClientId client, bool joined, const physics::wire::Hello& hello,
                                Simulation& simulation, const std::string& address,
                                std::uint64_t now) {
  HelloDecision decision;
  if (joined) {
    return refuse(std::move(decision), physics::wire::ERROR_UNEXPECTED_MESSAGE,
                  "a second Hello on the same connection", DropReason::UnexpectedMessage);
  }
  decision.name = printable_name(hello.client_name());
  if (hello.protocol_version() != wire::kProtocolVersion) {
    return refuse(std::move(decision), physics::wire::ERROR_PROTOCOL_VERSION,
                  "client speaks protocol version " + std::to_string(hello.protocol_version()) +
                      ", this server speaks version " + std::to_string(wire::kProtocolVersion),
                  DropReason::ProtocolVersion);
  }
  if (tickets_.required()) {
    ticket::Ticket ticket;
    if (std::string problem =
            tickets_.check(hello.access_token(), now, simulation.scene().name, ticket);
        !problem.empty()) {
      return refuse(std::move(decision), physics::wire::ERROR_BAD_TOKEN, std::move(problem),
                    DropReason::BadToken);
    }
    decision.ticket = std::move(ticket);
  } else if (token_ && !same_token(hello.access_token(), *token_)) {
    return refuse(std::move(decision), physics::wire::ERROR_BAD_TOKEN,
                  hello.access_token().empty() ? "this server requires an access token"
                                               : "wrong access token",
                  DropReason::BadToken);
  }
  if (std::string problem = wire::resolve_view(hello.view(), max_snapshot_window_, decision.view);
      !problem.empty()) {
    return refuse(std::move(decision), physics::wire::ERROR_INVALID_VIEW, std::move(problem),
                  DropReason::InvalidView);
  }
  if (decision.view.encoding == physics::wire::ENCODING_INPUTS && !hello.want_world()) {
    return refuse(std::move(decision), physics::wire::ERROR_INVALID_VIEW,
                  "view.encoding ENCODING_INPUTS relays inputs, not bodies: it needs "
                  "Hello.want_world, for the world to step them in",
                  DropReason::InvalidView);
  }
  if (hello.run_rules() && decision.view.encoding != physics::wire::ENCODING_INPUTS) {
    return refuse(std::move(decision), physics::wire::ERROR_INVALID_VIEW,
                  "Hello.run_rules runs the rules on the input relay: it needs view.encoding "
                  "ENCODING_INPUTS and Hello.want_world",
                  DropReason::InvalidView);
  }
  if (hello.has_contacts()) {
    ContactFilter contacts;
    if (std::string problem = resolve_contacts(hello.contacts(), hello.spectate(), contacts);
        !problem.empty()) {
      return refuse(std::move(decision), physics::wire::ERROR_INVALID_SUBSCRIPTION,
                    std::move(problem), DropReason::InvalidSubscription);
    }
    decision.contacts = std::move(contacts);
  }
  decision.sensor_events = hello.sensor_events();
  const bool spectator = hello.spectate();
  decision = spectator ? decide_spectator(client, std::move(decision))
                       : decide_player(client, hello, simulation, address, std::move(decision));
  if (decision.outcome != HelloDecision::Outcome::Refused && decision.ticket) {
    tickets_.admitted(client, *decision.ticket,
                      spectator ? std::nullopt : std::optional<std::uint32_t>(decision.seat));
  }
  return decision;
}

HelloDecision Handshake::decide_spectator(ClientId client, HelloDecision decision) {
  if (decision.view.interest == wire::InterestKind::Radius) {
    return refuse(std::move(decision), physics::wire::ERROR_INVALID_VIEW,
                  "view.interest_radius needs a body to be around; a spectator may use "
                  "view.interest_rect",
                  DropReason::InvalidView);
  }
  if (spectators_.size() >= max_spectators_) {
    return refuse(std::move(decision), physics::wire::ERROR_SERVER_FULL,
                  "no room to watch: " + std::to_string(max_spectators_) + " spectators connected",
                  DropReason::ServerFull);
  }
  spectators_.insert(client);
  decision.outcome = HelloDecision::Outcome::Spectator;
  return decision;
}

HelloDecision Handshake::decide_player(ClientId client, const physics::wire::Hello& hello,
                                       Simulation& simulation, const std::string& address,
                                       HelloDecision decision) {
  // The room holds exactly the players welcomed and not gone (a straggler leaves it,
  // and its seat, before its connection closes).
  if (simulation.room().size() + lobby_.size() >= max_clients_) {
    return refuse(std::move(decision), physics::wire::ERROR_SERVER_FULL,
                  "server full: " + std::to_string(max_clients_) + " clients connected",
                  DropReason::ServerFull);
  }
  if (max_players_per_address_ > 0 && !address.empty()) {
    const auto from = players_from_.find(address);
    if (from != players_from_.end() && from->second >= max_players_per_address_) {
      return refuse(std::move(decision), physics::wire::ERROR_SERVER_FULL,
                    "too many players from " + address + ": " +
                        std::to_string(max_players_per_address_) +
                        " joined (--max-players-per-address)",
                    DropReason::AddressFull);
    }
  }
  std::optional<std::uint32_t> wanted =
      hello.has_seat() ? std::optional<std::uint32_t>(hello.seat()) : std::nullopt;
  if (decision.ticket) {
    TicketAdmission::SeatChoice choice = tickets_.choose_seat(*decision.ticket, wanted, seats_);
    if (!choice.refusal.empty()) {
      return refuse(std::move(decision), choice.code, std::move(choice.refusal),
                    choice.code == physics::wire::ERROR_SERVER_FULL ? DropReason::ServerFull
                                                                    : DropReason::SeatTaken);
    }
    wanted = choice.seat;
  }
  const SeatTable::Claim claim = seats_.claim(client, wanted);
  switch (claim.outcome) {
    case SeatTable::Outcome::Seated:
      break;
    case SeatTable::Outcome::Taken:
      return refuse(std::move(decision), physics::wire::ERROR_SEAT_TAKEN,
                    "seat " + std::to_string(claim.seat) + " is taken", DropReason::SeatTaken);
    case SeatTable::Outcome::OutOfRange:
      return refuse(std::move(decision), physics::wire::ERROR_SEAT_OUT_OF_RANGE,
                    "seat " + std::to_string(claim.seat) + " is out of range: seats are 0 to " +
                        std::to_string(seats_.size() - 1),
                    DropReason::SeatOutOfRange);
    case SeatTable::Outcome::Full:
      return refuse(std::move(decision), physics::wire::ERROR_SERVER_FULL,
                    "server full: all " + std::to_string(seats_.size()) + " seats are taken",
                    DropReason::ServerFull);
  }
  decision.seat = claim.seat;
  // Counted from its seat on; a refusal below (no spawn) forgets it again.
  if (!address.empty()) {
    player_address_[client] = address;
    ++players_from_[address];
  }
  if (!lobby_open_) {
    lobby_.emplace(client, decision.view);
    decision.outcome = HelloDecision::Outcome::Lobby;
    decision.lobby_full = seats_.full();
    return decision;
  }
  // Outside a lobby a seat moves the body only when the Hello asked for it, so that
  // clients that name no seat spawn as they always did.
  const Admission admitted = simulation.admit(client, wanted);
  if (!admitted.body) {
    seats_.release(client);
    forget_address(client);
    if (admitted.refused) {
      return refuse(std::move(decision), physics::wire::ERROR_REFUSED_BY_GAME,
                    "refused by the game: " + *admitted.refused, DropReason::RefusedByGame);
    }
    return refuse(std::move(decision), physics::wire::ERROR_NO_SPAWN,
                  "no free spawn position for another body", DropReason::NoSpawn);
  }
  decision.body = *admitted.body;
  decision.outcome = HelloDecision::Outcome::Player;
  return decision;
}

LobbyOpening Handshake::open_lobby(Simulation& simulation) {
  lobby_open_ = true;
  LobbyOpening opening;
  for (const ClientId id : seats_.in_seat_order()) {
    const auto seated = lobby_.find(id);
    if (seated == lobby_.end()) continue;
    const std::uint32_t seat = *seats_.seat_of(id);
    const Admission admitted = simulation.admit(id, seat);
    if (!admitted.body) {
      seats_.release(id);
      forget_address(id);
      if (admitted.refused) {
        opening.refused.push_back({id, *admitted.refused});
      } else {
        opening.no_spawn.push_back(id);
      }
      continue;
    }
    opening.welcomed.push_back({id, *admitted.body, seat, seated->second});
  }
  lobby_.clear();
  return opening;
}

void Handshake::forget_address(ClientId client) {
  const auto it = player_address_.find(client);
  if (it == player_address_.end()) return;
  if (const auto from = players_from_.find(it->second);
      from != players_from_.end() && --from->second == 0) {
    players_from_.erase(from);
  }
  player_address_.erase(it);
}

Handshake::Member Handshake::leave(ClientId client) {
  forget_address(client);
  tickets_.left(client);
  if (spectators_.erase(client) > 0) return Member::Spectator;
  if (lobby_.erase(client) > 0) {
    seats_.release(client);
    return Member::Lobby;
  }
  // Every player holds a seat from its Hello until its connection closes.
  if (seats_.release(client)) return Member::Player;
  return Member::None;
}

}  // namespace server
