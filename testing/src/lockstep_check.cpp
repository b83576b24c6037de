#include "physics_testing/lockstep_check.h"

#include <algorithm>
#include <exception>
#include <string>
#include <thread>

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

// Checks that `clients` are lockstep players joined at one tick with exact views
// and the state hash, and adds their bodies to `reference`, which must give the
// same ids. Returns the tick they joined at.
Expected<std::uint64_t> prepare_reference(const Clients& clients, ReferenceRun& reference) {
  if (clients.empty()) return Expected<std::uint64_t>::failure("no clients to drive");
  const std::uint64_t start_tick = clients.front()->welcome().current_tick;
  for (std::size_t k = 0; k < clients.size(); ++k) {
    const client::Welcome& welcome = clients[k]->welcome();
    const std::string who = "client " + std::to_string(k);
    if (clients[k]->state() != client::ConnectionState::Connected) {
      return Expected<std::uint64_t>::failure(who + " is not connected");
    }
    if (welcome.spectator || !welcome.lockstep) {
      return Expected<std::uint64_t>::failure(who + " is not a player of a lockstep server");
    }
    if (welcome.view.encoding == client::Encoding::Predicted || !welcome.view.state_hash) {
      return Expected<std::uint64_t>::failure(
          who + " has no exact view with the state hash (use exact_client_config)");
    }
    if (welcome.current_tick != start_tick) {
      return Expected<std::uint64_t>::failure("the clients joined at different ticks (" +
                                              std::to_string(start_tick) + " and " +
                                              std::to_string(welcome.current_tick) + ")");
    }
  }
  // The server adds bodies one after another, so their ids ascend in join order; the
  // reference adds them in the same order and must get the same ids.
  reference.advance_to(start_tick);
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
      return Expected<std::uint64_t>::failure(error.what());
    }
    if (id != c->welcome().body_id) {
      return Expected<std::uint64_t>::failure("the in-process world gave body " +
                                              std::to_string(id) + " where the server gave " +
                                              std::to_string(c->welcome().body_id));
    }
  }
  return start_tick;
}

}  // namespace

Expected<LockstepRun> compare_lockstep_run(const scene::SceneDef& scene, const Clients& clients,
                                           const InputScript& script, std::uint64_t ticks,
                                           std::chrono::milliseconds snapshot_timeout) {
  ReferenceRun reference(scene);
  const Expected<std::uint64_t> start = prepare_reference(clients, reference);
  if (!start) return fail(start.message());
  LockstepRun run;
  run.start_tick = *start;

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

Expected<PacedLockstepRun> run_paced_lockstep(const scene::SceneDef& scene, const Clients& clients,
                                              const InputScript& script,
                                              const PacedLockstepOptions& options) {
  ReferenceRun reference(scene);
  const Expected<std::uint64_t> start = prepare_reference(clients, reference);
  if (!start) return Expected<PacedLockstepRun>::failure(start.message());
  PacedLockstepRun run;
  run.start_tick = *start;
  run.clients.resize(clients.size());
  const std::uint64_t last = run.start_tick + options.ticks;
  const auto deadline = std::chrono::steady_clock::now() + options.timeout;
  {
    // One thread a client: each is a player on its own clock, as over a real network.
    std::vector<std::jthread> threads;
    for (std::size_t k = 0; k < clients.size(); ++k) {
      threads.emplace_back([&, k] {
        client::Client& c = *clients[k];
        PacedClientRun& out = run.clients[k];
        out.hashes.assign(options.ticks, std::nullopt);
        out.arrivals.assign(options.ticks, std::nullopt);
        client::InputPacer pacer(c, options.pacer);
        const auto input = [&](std::uint64_t tick) { return script(k, tick); };
        while (pacer.last_sent() < last || out.newest_tick < last) {
          auto snapshot = pacer.poll(deadline, input);
          if (!snapshot) break;
          out.newest_tick = std::max(out.newest_tick, snapshot->tick);
          if (snapshot->tick > run.start_tick && snapshot->tick <= last) {
            out.hashes[snapshot->tick - run.start_tick - 1] = snapshot->state_hash;
            out.arrivals[snapshot->tick - run.start_tick - 1] = snapshot->received_at;
          }
          out.delays.push_back(pacer.clock().delay());
          if (options.on_snapshot) options.on_snapshot(k, snapshot->tick);
        }
        out.pacer = pacer.stats();
        out.raises = pacer.clock().raises();
        out.final_delay = pacer.clock().delay();
        if (out.newest_tick < last) {
          out.failure = "saw tick " + std::to_string(out.newest_tick) + " of " +
                        std::to_string(last) + ": " +
                        (c.state() == client::ConnectionState::Connected
                             ? std::string("the run's time ran out")
                             : c.last_error().to_string());
        }
      });
    }
  }
  for (std::size_t k = 0; k < clients.size(); ++k) {
    if (!run.clients[k].failure.empty()) {
      return Expected<PacedLockstepRun>::failure("client " + std::to_string(k) + " " +
                                                 run.clients[k].failure);
    }
  }
  for (std::uint64_t i = 1; i <= options.ticks; ++i) {
    const std::uint64_t tick = run.start_tick + i;
    for (std::size_t k = 0; k < clients.size(); ++k) {
      const client::Vec2 a = script(k, tick);
      reference.set_input(clients[k]->welcome().body_id, a.x, a.y);
    }
    const std::uint64_t expected = reference.step();
    run.hashes.push_back(expected);
    for (std::size_t k = 0; k < clients.size(); ++k) {
      const std::optional<std::uint64_t>& got = run.clients[k].hashes[i - 1];
      if (!got) {
        ++run.clients[k].missing;
        continue;
      }
      if (*got != expected) {
        return Expected<PacedLockstepRun>::failure(
            "tick " + std::to_string(tick) + ", client " + std::to_string(k) +
            ": the server's state hash " + hex(*got) + " differs from the in-process world's " +
            hex(expected));
      }
    }
  }
  return run;
}

}  // namespace physics_testing
