#pragma once
// Admission by connect ticket (--ticket-key-file; docs/PROTOCOL.md, "Connect
// tickets"), for the handshake: which Hellos carry a valid ticket, which player ids
// are connected (a ticket is refused while its player is), and, in a lockstep lobby,
// which seat each player id holds. No clock: the caller passes the time in.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "seats.h"
#include "server/room.h"
#include "ticket/ticket.h"
#include "wire.pb.h"

namespace server {

class TicketAdmission {
 public:
  // `key`: none, and tickets are not asked for. `room`: the room tickets must name
  // (when they name one); empty, the scene's. `hold_seats`: a lockstep lobby, where a
  // seat once taken stays held for its player id for the rest of the server's life.
  TicketAdmission(std::optional<ticket::Key> key, std::string room, bool hold_seats)
      : key_(key), room_(std::move(room)), hold_seats_(hold_seats) {}

  bool required() const { return key_.has_value(); }

  // The Hello's ticket checked at `now` (unix seconds) for a server running
  // `scene_name`: empty and `out` filled, or why it is refused.
  std::string check(const std::string& access_token, std::uint64_t now, std::string_view scene_name,
                    ticket::Ticket& out) const;

  struct SeatChoice {
    std::optional<std::uint32_t> seat;  // the seat to claim; none: as without tickets
    std::string refusal;                // non-empty: refused with `code`
    physics::wire::ErrorCode code = physics::wire::ERROR_UNSPECIFIED;
  };
  // The seat a ticket's player takes: the one its player id holds, else the ticket's,
  // else Hello.seat, else (holding seats) the lowest seat that is free and held for
  // no other player. A seat held for another player id is refused.
  SeatChoice choose_seat(const ticket::Ticket& ticket, std::optional<std::uint32_t> hello_seat,
                         const SeatTable& seats) const;

  // The client was admitted with `ticket` (as a player in `seat`, or a spectator).
  void admitted(ClientId client, const ticket::Ticket& ticket, std::optional<std::uint32_t> seat);
  // The client's connection closed: its player id may connect again.
  void left(ClientId client);

 private:
  std::optional<std::uint32_t> held_seat(std::uint64_t player_id) const;

  std::optional<ticket::Key> key_;
  std::string room_;
  bool hold_seats_;
  std::map<std::uint64_t, ClientId> connected_;  // player id -> its connection
  std::map<ClientId, std::uint64_t> player_of_;
  std::map<std::uint32_t, std::uint64_t> seat_holder_;  // seat -> player id (hold_seats)
};

}  // namespace server
