#include "physics_testing/lockstep_check.h"

#include <algorithm>
#include <exception>
#include <string>

#include "physics_testing/reference_run.h"

namespace physics_testing {

namespace {

Expected<LockstepRun> fail(std::string message) {
  return Expected<LockstepRun>::failure(std::move(message));
}

std::string hex(std::uint64_t value) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text = "0x0000000000000000";
  for (int i = 0; i < 16; ++i) text[17 - i] = kDigits[(value >> (4 * i)) & 0xf];
  return text;
}

}  // namespace

Expected<LockstepRun> compare_lockstep_run(const scene::SceneDef& scene, const Clients& clients,
                                           const InputScript& script, std::uint64_t ticks,
                                           std::chrono::milliseconds snapshot_timeout) {
  if (clients.empty()) return fail("no clients to drive");
  LockstepRun run;
  run.start_tick = clients.front()->welcome().current_tick;
  for (std::size_t k = 0; k < clients.size(); ++k) {
    const client::Welcome& welcome = clients[k]->welcome();
    if (clients[k]->state() != client::ConnectionState::Connected) {
      return fail("client " + std::to_string(k) + " is not connected");
    }
    if (welcome.spectator || !welcome.lockstep) {
      return fail("client " + std::to_string(k) + " is not a player of a lockstep server");
    }
    if (welcome.view.encoding == client::Encoding::Predicted || !welcome.view.state_hash) {
      return fail("client " + std::to_string(k) +
                  " has no exact view with the state hash (use exact_client_config)");
    }
    if (welcome.current_tick != run.start_tick) {
      return fail("the clients joined at different ticks (" + std::to_string(run.start_tick) +
                  " and " + std::to_string(welcome.current_tick) + ")");
    }
  }

  // The server adds bodies one after another, so their ids ascend in join order; the
  // reference adds them in the same order and must get the same ids.
  ReferenceRun reference(scene);
  reference.advance_to(run.start_tick);
  std::vector<const client::Client*> by_body;
  for (const auto& c : clients) by_body.push_back(c.get());
  std::sort(by_body.begin(), by_body.end(), [](const client::Client* a, const client::Client* b) {
    return a->welcome().body_id < b->welcome().body_id;
  });
  for (const client::Client* c : by_body) {
    std::uint64_t id = 0;
    try {
      id = reference.add_player(c->welcome());
    } catch (const std::exception& error) {
      return fail(error.what());
    }
    if (id != c->welcome().body_id) {
      return fail("the in-process world gave body " + std::to_string(id) +
                  " where the server gave " + std::to_string(c->welcome().body_id));
    }
  }

  for (std::uint64_t i = 1; i <= ticks; ++i) {
    const std::uint64_t tick = run.start_tick + i;
    for (std::size_t k = 0; k < clients.size(); ++k) {
      const client::Vec2 a = script(k, tick);
      if (!clients[k]->send_input(tick, a.x, a.y)) {
        return fail("client " + std::to_string(k) + " could not send its input for tick " +
                    std::to_string(tick) + ": " + clients[k]->last_error().to_string());
      }
      reference.set_input(clients[k]->welcome().body_id, a.x, a.y);
    }
    const std::uint64_t expected = reference.step();
    for (std::size_t k = 0; k < clients.size(); ++k) {
      // Heartbeats repeat the last tick; the snapshot of `tick` comes after them.
      Expected<client::Snapshot> snapshot = wait_for_snapshot(
          *clients[k], [&](const client::Snapshot& s) { return s.tick >= tick; }, snapshot_timeout,
          "tick " + std::to_string(tick));
      if (!snapshot) return fail("client " + std::to_string(k) + ": " + snapshot.message());
      if (snapshot->tick != tick) {
        return fail("client " + std::to_string(k) + " got tick " + std::to_string(snapshot->tick) +
                    " where tick " + std::to_string(tick) +
                    " was due (a tick was stepped without every input?)");
      }
      if (snapshot->state_hash != expected) {
        return fail("tick " + std::to_string(tick) + ", client " + std::to_string(k) +
                    ": the server's state hash " + hex(snapshot->state_hash) +
                    " differs from the in-process world's " + hex(expected));
      }
    }
    run.hashes.push_back(expected);
  }
  return run;
}

}  // namespace physics_testing
