#pragma once
// How early each player's inputs reach the server, measured against the time the tick
// they name is due: what a client needs to choose how far ahead to send them
// (docs/PROTOCOL.md 3.4, "Input delay"). An input's margin is due(tick) - arrival:
// positive when it waited in the buffer, negative when it was late (lockstep waited
// for it, or, at a fixed rate, it was applied a tick late). Each snapshot a client is
// sent carries the least margin of its inputs since the previous one
// (Snapshot.input_margin_us). No sockets and no clock: time is passed in.
#include <chrono>
#include <cstdint>
#include <map>
#include <optional>

#include "server/room.h"

namespace server {

class InputTiming {
 public:
  using time_point = std::chrono::steady_clock::time_point;

  // `period`: one tick. `idle_gap`: when the first input for a tick arrives longer
  // than this after the tick's scheduled time, nobody was sending (the lockstep
  // server sat idle): the tick counts as due when that first input arrived.
  InputTiming(std::chrono::nanoseconds period, std::chrono::nanoseconds idle_gap);

  // An accepted input of `client` that names `tick` arrived at `at`.
  void arrived(ClientId client, std::uint64_t tick, time_point at);
  // Tick `tick` is being stepped. `scheduled`: when it was due by the server's pace
  // (nullopt: no schedule yet, the first tick of a lockstep run). Returns the time it
  // counts as due, which the margins of the inputs that named it are taken against.
  time_point stepped(std::uint64_t tick, std::optional<time_point> scheduled);
  // The least margin among `client`'s inputs measured since the last call; nullopt
  // when none was.
  std::optional<std::chrono::microseconds> take_least_margin(ClientId client);
  void forget(ClientId client) { clients_.erase(client); }

 private:
  struct Client {
    std::map<std::uint64_t, time_point> waiting;  // arrival of the input for each tick
    std::optional<std::chrono::nanoseconds> least;
    void note(std::chrono::nanoseconds margin) {
      if (!least || margin < *least) least = margin;
    }
  };

  std::chrono::nanoseconds period_;
  std::chrono::nanoseconds idle_gap_;
  std::map<ClientId, Client> clients_;
  std::optional<std::uint64_t> last_tick_;
  time_point last_due_{};
};

}  // namespace server
