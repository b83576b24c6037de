#include "ticket_admission.h"

namespace server {

std::string TicketAdmission::check(const std::string& access_token, std::uint64_t now,
                                   std::string_view scene_name, ticket::Ticket& out) const {
  const std::string_view room = room_.empty() ? scene_name : std::string_view(room_);
  ticket::Checked checked = ticket::check(access_token, *key_, now, room);
  if (checked.problem == ticket::Problem::WrongRoom) {
    return "the ticket is for room '" + checked.ticket.room + "', this server is room '" +
           std::string(room) + "'";
  }
  if (checked.problem != ticket::Problem::None) return ticket::describe(checked.problem);
  if (connected_.count(checked.ticket.player_id) != 0) {
    return "the ticket's player " + std::to_string(checked.ticket.player_id) +
           " is connected already: a ticket admits one connection at a time";
  }
  out = std::move(checked.ticket);
  return {};
}

std::optional<std::uint32_t> TicketAdmission::held_seat(std::uint64_t player_id) const {
  for (const auto& [seat, holder] : seat_holder_) {
    if (holder == player_id) return seat;
  }
  return std::nullopt;
}

TicketAdmission::SeatChoice TicketAdmission::choose_seat(const ticket::Ticket& ticket,
                                                         std::optional<std::uint32_t> hello_seat,
                                                         const SeatTable& seats) const {
  SeatChoice choice;
  if (ticket.seat && hello_seat && *hello_seat != *ticket.seat) {
    choice.code = physics::wire::ERROR_SEAT_TAKEN;
    choice.refusal = "Hello.seat " + std::to_string(*hello_seat) + " is not the ticket's seat " +
                     std::to_string(*ticket.seat);
    return choice;
  }
  const std::optional<std::uint32_t> wanted = ticket.seat ? ticket.seat : hello_seat;
  if (!hold_seats_) {
    choice.seat = wanted;
    return choice;
  }
  if (const auto held = held_seat(ticket.player_id)) {
    if (wanted && *wanted != *held) {
      choice.code = physics::wire::ERROR_SEAT_TAKEN;
      choice.refusal = "player " + std::to_string(ticket.player_id) + " holds seat " +
                       std::to_string(*held) + " in this match, not seat " +
                       std::to_string(*wanted);
      return choice;
    }
    choice.seat = held;
    return choice;
  }
  if (wanted) {
    if (seat_holder_.count(*wanted) != 0) {
      choice.code = physics::wire::ERROR_SEAT_TAKEN;
      choice.refusal = "seat " + std::to_string(*wanted) + " is held for another player";
      return choice;
    }
    choice.seat = wanted;
    return choice;
  }
  for (std::uint32_t seat = 0; seat < seats.size(); ++seat) {
    if (seat_holder_.count(seat) == 0 && seats.is_free(seat)) {
      choice.seat = seat;
      return choice;
    }
  }
  choice.code = physics::wire::ERROR_SERVER_FULL;
  choice.refusal = "server full: every seat is taken or held for another player";
  return choice;
}

void TicketAdmission::admitted(ClientId client, const ticket::Ticket& ticket,
                               std::optional<std::uint32_t> seat) {
  connected_[ticket.player_id] = client;
  player_of_[client] = ticket.player_id;
  if (hold_seats_ && seat) seat_holder_.emplace(*seat, ticket.player_id);
}

void TicketAdmission::left(ClientId client) {
  const auto it = player_of_.find(client);
  if (it == player_of_.end()) return;
  connected_.erase(it->second);
  player_of_.erase(it);
}

}  // namespace server
