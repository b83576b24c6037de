#pragma once
// What a Hello leads to, without sockets: refused (a fatal Error: its code, text and
// drop reason), welcomed as a player with a body, welcomed as a spectator, or seated
// in the lockstep lobby to wait for the other players. The checks run in the order
// docs/PROTOCOL.md 3.1 gives, which is the contract with clients: protocol version,
// token, view, contact subscription, room, seat, spawn. The handshake holds who is
// in (seats, the lobby, the spectators); the world's bodies are the Simulation's.
// Server::Impl carries each decision out (sends, closes, registers the feeds);
// tests drive this class alone.
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "contact_subscription.h"
#include "physics/body.h"
#include "seats.h"
#include "server/server.h"
#include "server/simulation.h"
#include "ticket_admission.h"
#include "wire.pb.h"
#include "wire/view_settings.h"

namespace server {

// Client names in the log are at most this long.
inline constexpr std::size_t kMaxClientNameBytes = 64;

// For the log: a client's name is whatever it sent; keep it printable and short
// (kMaxClientNameBytes, control characters as '?').
std::string printable_name(const std::string& raw);

// Compares without stopping at the first difference, so the time taken does not
// tell an attacker how much of the token was right.
bool same_token(const std::string& given, const std::string& expected);

// The ways a Hello can fail that count against its address: a stranger guessing or
// fuzzing. Not the server's own limits (full, no spawn), nor a client that leaves.
bool is_failed_hello(DropReason reason);

// A fatal Error for the connection that sent the Hello.
struct Refusal {
  physics::wire::ErrorCode code = physics::wire::ERROR_UNSPECIFIED;
  std::string text;
  DropReason reason = DropReason::Malformed;
};

struct HelloDecision {
  enum class Outcome { Refused, Player, Spectator, Lobby };
  Outcome outcome = Outcome::Refused;
  Refusal refusal;   // Refused
  std::string name;  // printable_name of Hello.client_name
  // The Hello's contact subscription, once it passed its check: the server holds it
  // from then on, even when a later check refuses the Hello (the connection's close
  // forgets it).
  std::optional<ContactFilter> contacts;
  bool sensor_events = false;  // Hello.sensor_events, held as the contacts are
  wire::ViewSettings view;                      // all but Refused
  phys::BodyId body = phys::BodyId::invalid();  // Player: its body, in the world now
  std::uint32_t seat = 0;                       // Player, Lobby
  bool lobby_full = false;                      // Lobby: the last seat; open_lobby() next
  // All but Refused, when tickets are required: the connect ticket it came in with.
  std::optional<ticket::Ticket> ticket;
};

// A player welcomed when the lobby opened.
struct LobbyWelcome {
  ClientId client = 0;
  phys::BodyId body = phys::BodyId::invalid();
  std::uint32_t seat = 0;
  wire::ViewSettings view;
};

struct LobbyOpening {
  std::vector<LobbyWelcome> welcomed;  // in seat order
  // No free spawn position was left for them: refused with ERROR_NO_SPAWN, seats freed.
  std::vector<ClientId> no_spawn;
  // The game rules refused them (GameRules::on_join): ERROR_REFUSED_BY_GAME, with why.
  std::vector<std::pair<ClientId, std::string>> refused;
};

class Handshake {
 public:
  // Reads token, ticket_key, ticket_room, max_clients, max_spectators,
  // max_snapshot_window and lockstep_players (N > 0: N seats and a lobby; else
  // max_clients seats).
  explicit Handshake(const ServerConfig& config);

  // `joined`: the connection was already welcomed or seated (a second Hello). A
  // player that passes every check is given its seat and its body in `simulation`.
  // `address`: where it connects from, for max_players_per_address. `now`: unix
  // seconds, read by the network layer, against which a connect ticket expires.
  HelloDecision decide(ClientId client, bool joined, const physics::wire::Hello& hello,
                       Simulation& simulation, const std::string& address = {},
                       std::uint64_t now = 0);
  // Every seat is taken: the lobby's bodies are made in seat order (each at its seat's
  // spawn point when free), so that the world, body ids included, is the same whatever
  // order the players connected in. The lobby is empty and open afterwards.
  LobbyOpening open_lobby(Simulation& simulation);

  enum class Member { None, Player, Lobby, Spectator };
  // Forgets a client whose connection closed, freeing its seat; says what it was.
  // A player's body is the Simulation's to remove.
  Member leave(ClientId client);

  bool is_spectator(ClientId client) const { return spectators_.count(client) > 0; }
  std::size_t spectator_count() const { return spectators_.size(); }
  std::size_t lobby_size() const { return lobby_.size(); }
  bool in_lobby(ClientId client) const { return lobby_.count(client) > 0; }
  // True without a lobby; with one, once every seat was taken.
  bool lobby_open() const { return lobby_open_; }
  const SeatTable& seats() const { return seats_; }

 private:
  HelloDecision decide_spectator(ClientId client, HelloDecision decision);
  HelloDecision decide_player(ClientId client, const physics::wire::Hello& hello,
                              Simulation& simulation, const std::string& address,
                              HelloDecision decision);
  // Forgets a seated player's address (its count per address).
  void forget_address(ClientId client);

  std::optional<std::string> token_;
  TicketAdmission tickets_;
  std::size_t max_clients_;
  std::size_t max_spectators_;
  std::uint32_t max_snapshot_window_;
  SeatTable seats_;
  std::map<ClientId, wire::ViewSettings> lobby_;  // seated players not yet welcomed
  bool lobby_open_;
  std::set<ClientId> spectators_;
  std::size_t max_players_per_address_;              // 0: no cap
  std::map<ClientId, std::string> player_address_;   // seated players (lobby included)
  std::map<std::string, std::size_t> players_from_;  // seated players per address
};

}  // namespace server
