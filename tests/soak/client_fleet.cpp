// The client fleet's script: joins, leaves, read stalls and inputs, and the tally
// of every snapshot a client took.
#include "client_fleet.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace soak {
namespace {

using namespace std::chrono_literals;

// Slot k's acceleration at tick t: changes every 5 ticks, small against any
// scene's max_acceleration.
std::pair<double, double> scripted_input(std::size_t k, std::uint64_t t) {
  const double phase = static_cast<double>(t / 5) * 0.7 + static_cast<double>(k) * 1.3;
  return {3.0 * std::cos(phase), 3.0 * std::sin(phase)};
}

}  // namespace

ClientFleet::ClientFleet(const Options& options, server::Server& server)
    : options_(options), server_(server), rng_(options.seed) {
  slots_.resize(static_cast<std::size_t>(options.clients));
  for (std::size_t k = 0; k < slots_.size(); ++k) slots_[k].index = k;
}

bool ClientFleet::join(Slot& slot) {
  client::ClientConfig config;
  config.port = server_.port();
  config.name = fmt::format("soak-{}", slot.index);
  config.view.state_hash = true;
  config.view.encoding = options_.encoding;
  auto player = std::make_unique<client::Client>(config);
  if (!player->connect(5s)) {
    const client::ClientError& error = player->last_error();
    if (error.server && error.server->code == client::ErrorCode::NoSpawn) {
      ++tally_.join_refused_no_spawn;
    } else {
      ++tally_.join_failures;
      fmt::print(stderr, "physics-soak: slot {} could not join: {}\n", slot.index,
                 error.to_string());
    }
    slot.rejoin_at = Clock::now() + 1s;
    return false;
  }
  slot.sent_through = player->welcome().current_tick;
  slot.reading_at = Clock::now();
  slot.client = std::move(player);
  ++tally_.joins;
  return true;
}

void ClientFleet::leave(Slot& slot, Clock::time_point now) {
  tally_.view_desyncs += slot.client->stats().desyncs;
  slot.client->disconnect("soak: leaving");
  slot.client.reset();
  ++tally_.leaves;
  slot.rejoin_at = now + std::chrono::milliseconds(500 + rng_() % 1500);
}

void ClientFleet::join_all() {
  for (Slot& slot : slots_) join(slot);
}

void ClientFleet::scripted_event(Clock::time_point now) {
  const std::uint64_t r = rng_();
  Slot& slot = slots_[r % slots_.size()];
  if (!slot.joined()) return;
  if ((r >> 32) % 2 == 0) {
    leave(slot, now);
  } else if (slot.reading_at <= now) {
    slot.reading_at = now + std::chrono::milliseconds(500 + rng_() % 2500);
    ++tally_.stalls;
  }
}

void ClientFleet::pass(Clock::time_point now) {
  for (Slot& slot : slots_) {
    if (!slot.joined()) {
      if (now >= slot.rejoin_at) join(slot);
      continue;
    }
    client::Client& player = *slot.client;
    if (now >= slot.reading_at) read(player);
    if (player.state() != client::ConnectionState::Connected) {
      lost(slot, now);
      continue;
    }
    send_inputs(slot);
    if (player.state() != client::ConnectionState::Connected) lost(slot, now);
  }
}

void ClientFleet::finish() {
  for (Slot& slot : slots_) {
    if (!slot.joined()) continue;
    read(*slot.client);
    tally_.view_desyncs += slot.client->stats().desyncs;
  }
}

std::uint64_t ClientFleet::joined() const {
  return static_cast<std::uint64_t>(
      std::count_if(slots_.begin(), slots_.end(), [](const Slot& slot) { return slot.joined(); }));
}

void ClientFleet::close_all() {
  for (Slot& slot : slots_) slot.client.reset();
}

// The client reads only inside its own calls, and a call with a zero timeout runs
// no socket handler: a 1 ms wait reads what has arrived, then the snapshots
// already buffered are taken without waiting.
void ClientFleet::read(client::Client& player) {
  if (auto snapshot = player.next_snapshot(1ms)) take(*snapshot);
  while (player.buffered_snapshots() > 0) {
    if (auto snapshot = player.next_snapshot(0ms)) take(*snapshot);
  }
}

void ClientFleet::take(const client::Snapshot& snapshot) {
  ++tally_.snapshots;
  tally_.global_tick = std::max(tally_.global_tick, snapshot.tick);
  ++tally_.hash_samples;
  const auto [it, inserted] = tally_.hashes.emplace(snapshot.tick, snapshot.state_hash);
  if (!inserted && it->second != snapshot.state_hash) ++tally_.cross_client_conflicts;
}

void ClientFleet::send_inputs(Slot& slot) {
  const std::uint64_t lead = options_.lockstep ? 8 : 4;
  const std::uint64_t through = tally_.global_tick + lead;
  // At a fixed rate the ticks go on without us: a slot far behind skips to now.
  if (!options_.lockstep && slot.sent_through + 2 * lead < tally_.global_tick) {
    slot.sent_through = tally_.global_tick;
  }
  while (slot.sent_through < through) {
    ++slot.sent_through;
    const auto [ax, ay] = scripted_input(slot.index, slot.sent_through);
    if (!slot.client->send_input(slot.sent_through, ax, ay)) return;
  }
}

void ClientFleet::lost(Slot& slot, Clock::time_point now) {
  ++tally_.lost_sessions;
  fmt::print(stderr, "physics-soak: slot {} lost its session: {}\n", slot.index,
             slot.client->last_error().to_string());
  tally_.view_desyncs += slot.client->stats().desyncs;
  slot.client.reset();
  slot.rejoin_at = now + 1s;
}

}  // namespace soak
