#pragma once
// The world's state hash (docs/PROTOCOL.md 5.11, phys::World::state_hash) computed
// by a client from what it was sent, without the scene file and without the core:
// the shapes (Welcome.bodies and Snapshot::added, less Snapshot::removed) for what
// never changes, and the states it holds for what moves. It equals the server's
// hash when the client holds every moving body exactly (Encoding::Exact or
// Encoding::Full, with the whole world in view) and every body's acceleration is
// still the one its shape was sent with (no player other than this one has sent an
// input since; a player passes its own).
#include <cstdint>
#include <optional>
#include <vector>

#include "client/types.h"

namespace client {

// An acceleration a client knows better than its shape: its own body's input.
struct KnownAcceleration {
  std::uint64_t body_id = 0;
  Vec2 acceleration;
};

// The hash, or nullopt when a moving shape has no state in `held` (the client does
// not hold it: out of its view, or not sent yet). `held` is Snapshot::bodies.
std::optional<std::uint64_t> state_hash(const std::vector<BodyShape>& shapes,
                                        const std::vector<BodyState>& held,
                                        const std::vector<KnownAcceleration>& known = {});

}  // namespace client
