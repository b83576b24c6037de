#pragma once
// The lockstep straggler policy: a player whose input was missing at `limit`
// consecutive ticks that stepped after a timeout is reported, to be dropped, so
// that one stopped client holds the others back for at most limit timeouts.
// A tick that steps with the player's input resets its count. 0: never drop.
#include <cstdint>
#include <map>
#include <vector>

#include "server/room.h"

namespace server {

class StragglerWatch {
 public:
  explicit StragglerWatch(int limit) : limit_(limit) {}

  // After a tick stepped: `missing` are the players without a fresh input for it,
  // `timed_out` whether it stepped after a lockstep timeout. Returns the players
  // who reached the limit with this tick (ascending id).
  std::vector<ClientId> after_step(const std::vector<ClientId>& missing, bool timed_out);
  void forget(ClientId client) { misses_.erase(client); }
  int misses(ClientId client) const;
  int limit() const { return limit_; }

 private:
  int limit_;
  std::map<ClientId, int> misses_;  // consecutive timed-out ticks missed
};

}  // namespace server
