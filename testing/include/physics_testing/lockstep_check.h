#pragma once
// A networked lockstep run held to the same scene stepped in-process, tick by tick,
// state hash by state hash: what a test asserts to say "the server computes exactly
// the world the inputs describe".
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "client/input_pacer.h"
#include "client/types.h"
#include "physics_testing/clients.h"
#include "physics_testing/game_run.h"
#include "physics_testing/outcome.h"
#include "scene/scene.h"

namespace physics_testing {

// Client k's acceleration at tick t.
using InputScript = std::function<client::Vec2(std::size_t client, std::uint64_t tick)>;

struct LockstepRun {
  std::uint64_t start_tick = 0;       // the tick every client joined at
  std::vector<std::uint64_t> hashes;  // the state hash after start_tick + 1, + 2, ...
};

// Drives `clients` for `ticks` ticks. They must be players joined to a lockstep
// server of `scene`, all at the same tick (no inputs sent yet), each with exact
// encoding and the state hash in its view (Endpoint::exact_client_config). At each
// tick client k sends script(k, tick), the scene is stepped in-process with the same
// inputs (ReferenceRun), and every client's snapshot of that tick must carry the
// reference's hash. The hashes, or a message naming the first tick and client that
// differ.
Expected<LockstepRun> compare_lockstep_run(
    const scene::SceneDef& scene, const Clients& clients, const InputScript& script,
    std::uint64_t ticks, std::chrono::milliseconds snapshot_timeout = std::chrono::seconds(5));

// The same for a game: the server runs `clients` with rules of the game (its
// config's), and the in-process run is the server's own tick logic
// (server::Simulation) with a fresh rules object from `rules`, stepped to the
// clients' tick, the clients joined in the order of their bodies under their
// client ids (without seats). Inputs only: a script's game messages are not sent.
Expected<LockstepRun> compare_lockstep_run(
    const scene::SceneDef& scene, const RulesFactory& rules, const Clients& clients,
    const InputScript& script, std::uint64_t ticks,
    std::chrono::milliseconds snapshot_timeout = std::chrono::seconds(5));

// The same over a real path: every client on its own thread, sending its inputs on
// its own clock ahead of the server (client::InputPacer), as a player does; the
// server's hash of every tick it was sent is held to the in-process run afterwards.
struct PacedLockstepOptions {
  std::uint64_t ticks = 120;
  client::PacerConfig pacer;
  std::chrono::milliseconds timeout{30000};  // for the whole run
  // Called on client k's thread with each snapshot's tick (e.g. to change the path).
  std::function<void(std::size_t client, std::uint64_t tick)> on_snapshot;
};

struct PacedClientRun {
  std::vector<std::optional<std::uint64_t>> hashes;  // of start_tick + 1, ...; unset: not sent
  // When the snapshot of start_tick + 1, ... arrived (unset: not sent).
  std::vector<std::optional<std::chrono::steady_clock::time_point>> arrivals;
  std::uint64_t newest_tick = 0;
  std::size_t missing = 0;            // ticks of the run it was sent no snapshot of
  std::vector<std::uint32_t> delays;  // the input delay after each snapshot
  std::uint32_t final_delay = 0;
  std::uint64_t raises = 0;  // times the delay grew (InputClock::raises)
  client::PacerStats pacer;
  std::string failure;
};

struct PacedLockstepRun {
  std::uint64_t start_tick = 0;
  std::vector<std::uint64_t> hashes;  // the in-process run's, after start_tick + 1, ...
  std::vector<PacedClientRun> clients;
};

// Drives `clients` (as for compare_lockstep_run) until each has seen tick
// start_tick + ticks. The run, or a message naming the first tick and client whose
// hash differs from the in-process run's, or a client that did not get there.
Expected<PacedLockstepRun> run_paced_lockstep(const scene::SceneDef& scene, const Clients& clients,
                                              const InputScript& script,
                                              const PacedLockstepOptions& options);

}  // namespace physics_testing
