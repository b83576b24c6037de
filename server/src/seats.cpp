#include "seats.h"

namespace server {

SeatTable::Claim SeatTable::claim(ClientId client, std::optional<std::uint32_t> wanted) {
  if (const auto held = seat_of(client)) return {Outcome::Seated, *held};
  if (wanted) {
    if (*wanted >= size_) return {Outcome::OutOfRange, *wanted};
    if (by_seat_.count(*wanted) != 0) return {Outcome::Taken, *wanted};
    by_seat_.emplace(*wanted, client);
    by_client_.emplace(client, *wanted);
    return {Outcome::Seated, *wanted};
  }
  // by_seat_ ascends: the first gap in 0, 1, 2, ... is the lowest free seat.
  std::uint32_t seat = 0;
  for (const auto& [taken_seat, holder] : by_seat_) {
    if (taken_seat != seat) break;
    ++seat;
  }
  if (seat >= size_) return {Outcome::Full, 0};
  by_seat_.emplace(seat, client);
  by_client_.emplace(client, seat);
  return {Outcome::Seated, seat};
}

bool SeatTable::release(ClientId client) {
  const auto it = by_client_.find(client);
  if (it == by_client_.end()) return false;
  by_seat_.erase(it->second);
  by_client_.erase(it);
  return true;
}

std::optional<std::uint32_t> SeatTable::seat_of(ClientId client) const {
  const auto it = by_client_.find(client);
  if (it == by_client_.end()) return std::nullopt;
  return it->second;
}

std::vector<ClientId> SeatTable::in_seat_order() const {
  std::vector<ClientId> clients;
  clients.reserve(by_seat_.size());
  for (const auto& [seat, client] : by_seat_) clients.push_back(client);
  return clients;
}

}  // namespace server
