#pragma once
// Applying the input relay to a world (docs/PROTOCOL.md 5.12): a RelayTick's body
// changes in order, its accelerations in order, one step, and its state hash
// checked. A world at tick T-1 that follows the RelayTick of T holds, bit for bit,
// the server's world after T.
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "physics/world.h"
#include "wire.pb.h"

namespace relay {

// The definition a RelayBody carries.
phys::BodyDef body_def(const physics::wire::RelayBody& body);

enum class FollowProblem {
  None,
  // A body added at another id than the server's, or removed where there is none:
  // the world was not the server's before this tick.
  BodyMismatch,
  // An acceleration for a body the world does not hold, or not finite.
  BadInput,
  // The tick's state hash differs from the world's after the step.
  HashMismatch,
};

struct FollowResult {
  FollowProblem problem = FollowProblem::None;
  std::string detail;  // for a person
  bool hash_checked = false;
};

// Applies the tick's changes, inputs and the rules' before_step changes to `world`,
// steps it by `dt`, applies the rules' after_step changes, then compares the state
// hash when the tick has one. On BodyMismatch or BadInput the
// world is left part-way and must be replaced (the server's world_state).
FollowResult follow(phys::World& world, const physics::wire::RelayTick& tick, double dt);

// Applies only the changes, the inputs and the rules' before_step changes, without
// stepping (a predicting client sets its own input in between; it then steps and
// applies after_step itself).
FollowResult apply_changes_and_inputs(phys::World& world, const physics::wire::RelayTick& tick);

// The rules' after_step changes, once the world has stepped.
FollowResult apply_after_step(phys::World& world, const physics::wire::RelayTick& tick);

// The world of a Welcome.world_state or Snapshot.world_state; nullopt and *error
// when the bytes are not a world (World::from_bytes).
std::optional<phys::World> world_from(const std::string& bytes, std::string* error = nullptr);

}  // namespace relay
