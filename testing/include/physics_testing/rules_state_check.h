#pragma once
// The check that a game's rules keep nothing outside the world (after GGPO's
// synctest): the game is run twice on the server's own tick logic, once as the
// server runs it (one rules object from start to end) and once with a fresh rules
// object from the factory before every tick. Rules that keep what they need from
// tick to tick in the world's game state (GameWorld::set_int, set_number,
// start_timer) and in the bodies give the same run both times; rules that keep a
// score, a cooldown or a cached id in a member of their own do not, and then a
// saved and restored world, a replay from a checkpoint, a resync or a late joiner's
// world would not hold what the game needs either.
#include <cstdint>
#include <functional>
#include <vector>

#include "physics_testing/game_run.h"
#include "physics_testing/outcome.h"
#include "scene/scene.h"

namespace physics_testing {

// What a test does before tick `tick` is stepped (joins, leaves, inputs, messages,
// placed bodies), the same in both runs. It must depend on nothing but the run it
// is given and the tick.
using GameScript = std::function<void(GameRun& run, std::uint64_t tick)>;

struct RulesStateCheck {
  std::vector<std::uint64_t> hashes;  // the state hash after ticks 1, 2, ...
  std::size_t messages = 0;           // the messages the rules sent in all
};

// Runs `ticks` ticks of `scene` with rules from `rules`, twice as said above, and
// compares every tick's state hash and the messages the rules sent (recipient and
// payload, in order). The run's hashes, or a message naming the first tick that
// differs and how. A rule that throws fails the check with its message.
Expected<RulesStateCheck> check_rules_state_in_world(const scene::SceneDef& scene,
                                                     const RulesFactory& rules,
                                                     const GameScript& script, std::uint64_t ticks);

}  // namespace physics_testing
