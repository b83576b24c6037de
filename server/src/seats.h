#pragma once
// Who plays in which seat. A seat is a number in [0, size): a Hello may ask for one
// (Hello.seat), otherwise the lowest free seat is given. In a lockstep lobby the
// seats, not the order connections land in, decide which body each player gets:
// bodies are made in seat order once every seat is taken (docs/PROTOCOL.md, "Seats").
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "server/room.h"

namespace server {

class SeatTable {
 public:
  explicit SeatTable(std::uint32_t size) : size_(size) {}

  enum class Outcome { Seated, Taken, OutOfRange, Full };
  struct Claim {
    Outcome outcome = Outcome::Full;
    std::uint32_t seat = 0;  // the seat given (Seated) or asked for
  };
  // Gives `client` the seat it asked for, or the lowest free one when `wanted` is
  // empty. A client already seated keeps its seat.
  Claim claim(ClientId client, std::optional<std::uint32_t> wanted);
  // Frees the client's seat; false when it held none.
  bool release(ClientId client);

  std::optional<std::uint32_t> seat_of(ClientId client) const;
  bool is_free(std::uint32_t seat) const { return seat < size_ && by_seat_.count(seat) == 0; }
  std::uint32_t size() const { return size_; }
  std::size_t taken() const { return by_seat_.size(); }
  bool full() const { return by_seat_.size() >= size_; }
  // Seated clients in ascending seat order.
  std::vector<ClientId> in_seat_order() const;

 private:
  std::uint32_t size_;
  std::map<std::uint32_t, ClientId> by_seat_;
  std::map<ClientId, std::uint32_t> by_client_;
};

}  // namespace server
