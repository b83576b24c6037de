#pragma once
// A player's loop against the fake server, in ticks: each round the client gives
// its input for the tick `lead` ahead of the server and predicts to it; the server
// steps one tick with the inputs scheduled; its relayed ticks reach the client
// `latency` rounds later. No clock, no sockets.
#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>

#include "client/prediction_core.h"
#include "fake_server.h"

namespace predicting_test {

struct PredictionLoop {
  explicit PredictionLoop(std::uint32_t lead_ticks = 6, std::uint32_t latency_rounds = 4,
                          std::uint32_t hash_interval = 1, client::PredictionConfig config = {})
      : server(2, hash_interval), core(config), lead(lead_ticks), latency(latency_rounds) {
    core.start(server.copy(), server.tick(), own(), server.tick_rate(), server.max_acceleration());
  }

  std::uint64_t own() const { return server.player(0); }
  std::uint64_t other() const { return server.player(1); }

  // One round: the own input for server.tick() + lead, the prediction to it, one
  // server tick, and the relayed ticks that have travelled `latency` rounds.
  void round(const std::function<client::Vec2(std::uint64_t)>& own_input) {
    const std::uint64_t local = server.tick() + lead;
    const client::Vec2 a = own_input(local);
    core.set_input(local, a);
    server.input(own(), local + own_late_by, a);
    core.advance_to(local);
    in_flight.push_back(server.step());
    while (in_flight.size() > latency) deliver_one();
  }

  void deliver_one() {
    before_delivery = core.predicted_tick() - core.confirmed_tick();
    core.on_snapshot(relay_snapshot({in_flight.front()}));
    in_flight.pop_front();
  }

  FakeServer server;
  client::PredictionCore core;
  std::uint32_t lead;
  std::uint32_t latency;
  // The server applies the own input this many ticks after the one it names (late).
  std::uint64_t own_late_by = 0;
  std::deque<physics::wire::RelayTick> in_flight;
  std::uint64_t before_delivery = 0;  // ticks in flight at the last delivery
};

// The own body circles: a different acceleration every tick.
inline client::Vec2 circling(std::uint64_t tick) {
  const double angle = static_cast<double>(tick % 120) * (2.0 * 3.141592653589793 / 120.0);
  return {5.0 * std::cos(angle), 5.0 * std::sin(angle)};
}

}  // namespace predicting_test
