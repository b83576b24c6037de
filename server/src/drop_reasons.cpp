// What each DropReason is called in the log, and the stats' totals over them.
#include "server/server.h"

namespace server {

const char* to_string(DropReason reason) {
  switch (reason) {
    case DropReason::ClientBye:
      return "said bye";
    case DropReason::Disconnected:
      return "disconnected";
    case DropReason::MessageTooLarge:
      return "message too large";
    case DropReason::Malformed:
      return "malformed message";
    case DropReason::ProtocolVersion:
      return "wrong protocol version";
    case DropReason::BadToken:
      return "bad token";
    case DropReason::ServerFull:
      return "server full";
    case DropReason::NoSpawn:
      return "no free spawn point";
    case DropReason::UnexpectedMessage:
      return "unexpected message";
    case DropReason::Idle:
      return "idle (nothing received)";
    case DropReason::TooSlow:
      return "too slow (not reading)";
    case DropReason::ShuttingDown:
      return "server shutting down";
    case DropReason::InvalidView:
      return "invalid view settings";
    case DropReason::HandshakeTimeout:
      return "no Hello in time";
    case DropReason::TooManyPending:
      return "too many connections not joined";
    case DropReason::AddressLimited:
      return "address refused (failed Hellos or connecting too fast)";
    case DropReason::InternalError:
      return "internal error handling its message";
    case DropReason::SeatTaken:
      return "seat taken";
    case DropReason::SeatOutOfRange:
      return "seat out of range";
    case DropReason::LockstepStraggler:
      return "lockstep straggler (missed too many ticks)";
    case DropReason::InvalidSubscription:
      return "invalid contact subscription";
    case DropReason::AddressFull:
      return "too many players from its address";
    case DropReason::SeatBackoff:
      return "address backing off after drops";
    case DropReason::NotReading:
      return "not reading (no snapshot acknowledged)";
    case DropReason::RefusedByGame:
      return "refused by the game";
  }
  return "unknown";
}

std::uint64_t ServerStats::dropped_total() const {
  std::uint64_t total = 0;
  for (const auto& [reason, count] : dropped) total += count;
  return total;
}

std::uint64_t ServerStats::dropped_by_fault() const {
  std::uint64_t total = 0;
  for (const auto& [reason, count] : dropped) {
    if (reason != DropReason::ClientBye && reason != DropReason::ShuttingDown) total += count;
  }
  return total;
}

}  // namespace server
