#include "physics_testing/lockstep_check.h"

#include <algorithm>
#include <exception>
#include <functional>
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
// and the state hash. Returns the tick they joined at.
Expected<std::uint64_t> check_clients(const Clients& clients) {
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
  return start_tick;
}

// check_clients, then adds their bodies to `reference`, which must give the same
// ids. Returns the tick they joined at.
Expected<std::uint64_t> prepare_reference(const Clients& clients, ReferenceRun& reference) {
  const Expected<std::uint64_t> checked = check_clients(clients);
  if (!checked) return checked;
  const std::uint64_t start_tick = *checked;
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

// The in-process side of a lockstep comparison: client k's input at a tick, then
// one tick stepped, giving its state hash.
struct InProcessSide {
  std::function<void(std::size_t client, std::uint64_t tick, client::Vec2 a)> input;
  std::function<std::uint64_t()> step;
};

// Sends each client its script's inputs tick by tick and holds every client's
// snapshot of each tick to the in-process side's hash.
Expected<LockstepRun> drive_lockstep(const Clients& clients, const InputScript& script,
                                     std::uint64_t ticks,
                                     std::chrono::milliseconds snapshot_timeout,
                                     std::uint64_t start_tick, const InProcessSide& reference) {
  LockstepRun run;
  run.start_tick = start_tick;
  for (std::uint64_t i = 1; i <= ticks; ++i) {
    const std::uint64_t tick = run.start_tick + i;
    for (std::size_t k = 0; k < clients.size(); ++k) {
      const client::Vec2 a = script(k, tick);
      if (!clients[k]->send_input(tick, a.x, a.y)) {
        return fail("client " + std::to_string(k) + " could not send its input for tick " +
                    std::to_string(tick) + ": " + clients[k]->last_error().to_string());
      }
      reference.input(k, tick, a);
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

// check_clients, and a Simulation with the game's rules
// stepped to their tick with their bodies, which must get the server's ids.
Expected<std::uint64_t> prepare_game(const Clients& clients, server::Simulation& reference) {
  const Expected<std::uint64_t> checked = check_clients(clients);
  if (!checked) return checked;
  const std::uint64_t start_tick = *checked;
  while (reference.current_tick() < start_tick) reference.step_tick();
  std::vector<const client::Client*> by_body;
  for (const auto& c : clients) by_body.push_back(c.get());
  std::sort(by_body.begin(), by_body.end(), [](const client::Client* a, const client::Client* b) {
    return a->welcome().body_id < b->welcome().body_id;
  });
  for (const client::Client* c : by_body) {
    const server::Admission admission = reference.admit(c->welcome().client_id);
    if (!admission.body) {
      return Expected<std::uint64_t>::failure(
          "the in-process game did not let client " + std::to_string(c->welcome().client_id) +
          " in: " + admission.refused.value_or("no free spawn point"));
    }
    if (admission.body->packed() != c->welcome().body_id) {
      return Expected<std::uint64_t>::failure(
          "the in-process game gave body " + std::to_string(admission.body->packed()) +
          " where the server gave " + std::to_string(c->welcome().body_id));
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
  const InProcessSide side{[&](std::size_t k, std::uint64_t /*tick*/, client::Vec2 a) {
                             reference.set_input(clients[k]->welcome().body_id, a.x, a.y);
                           },
                           [&] { return reference.step(); }};
  return drive_lockstep(clients, script, ticks, snapshot_timeout, *start, side);
}

Expected<LockstepRun> compare_lockstep_run(const scene::SceneDef& scene, const RulesFactory& rules,
                                           const Clients& clients, const InputScript& script,
                                           std::uint64_t ticks,
                                           std::chrono::milliseconds snapshot_timeout) {
  server::Simulation reference(scene, {}, rules());
  const Expected<std::uint64_t> start = prepare_game(clients, reference);
  if (!start) return fail(start.message());
  const InProcessSide side{
      [&](std::size_t k, std::uint64_t tick, client::Vec2 a) {
        reference.submit_input(clients[k]->welcome().client_id, tick, {a.x, a.y});
      },
      [&] {
        reference.step_tick();
        return reference.world().state_hash();
      }};
  return drive_lockstep(clients, script, ticks, snapshot_timeout, *start, side);
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
