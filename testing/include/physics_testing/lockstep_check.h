#pragma once
// A networked lockstep run held to the same scene stepped in-process, tick by tick,
// state hash by state hash: what a test asserts to say "the server computes exactly
// the world the inputs describe".
#include <chrono>
#include <cstdint>
#include <functional>
#include <vector>

#include "client/types.h"
#include "physics_testing/clients.h"
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

}  // namespace physics_testing
