// The game state in the world (physics/game_state.h, World::game_state): its values
// and refusals, its timers' order, and that save and restore, to_bytes and
// from_bytes and the state hash carry it, while a world without one hashes as it
// always did. Damaged game-state bytes are refused with a reason, never a crash.
#include "physics/game_state.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "physics/world.h"

namespace phys::testing {
namespace {

constexpr double kDt = 1.0 / 60.0;

World small_world() {
  World world;
  BodyDef floor;
  floor.motion = Motion::Static;
  floor.half_extents = {10.0, 0.5};
  floor.position = {0.0, -0.5};
  world.add_body(floor);
  BodyDef ball;
  ball.shape = Shape::Circle;
  ball.radius = 0.25;
  ball.position = {1.0, 3.0};
  ball.velocity = {2.0, 0.0};
  world.add_body(ball);
  return world;
}

// A state with one entry of each kind, and an index that is not 0.
void fill(GameState& state) {
  ASSERT_EQ(state.set_int("score", 1, 3), GameStateError::None);
  ASSERT_EQ(state.set_int("score", 2, -7), GameStateError::None);
  ASSERT_EQ(state.set_number("heat", 0, 0.125), GameStateError::None);
  ASSERT_EQ(state.start_timer("respawn", 2, 10, 15, 0), GameStateError::None);
  ASSERT_EQ(state.start_timer("wave", 0, 10, 12, 30), GameStateError::None);
}

TEST(GameState, HoldsTypedValuesUnderNameAndIndex) {
  GameState state;
  EXPECT_TRUE(state.empty());
  fill(state);
  EXPECT_EQ(state.size(), 5u);
  EXPECT_EQ(state.get_int("score", 1), 3);
  EXPECT_EQ(state.get_int("score", 2), -7);
  EXPECT_FALSE(state.get_int("score", 0).has_value());
  EXPECT_FALSE(state.get_int("heat").has_value()) << "numbers and integers are apart";
  EXPECT_EQ(state.get_number("heat"), 0.125);
  EXPECT_EQ(state.timer("respawn", 2), (GameTimer{15, 0}));
  EXPECT_TRUE(state.erase_int("score", 2));
  EXPECT_FALSE(state.erase_int("score", 2));
  EXPECT_TRUE(state.cancel_timer("wave"));
  EXPECT_FALSE(state.timer("wave").has_value());
  EXPECT_EQ(state.size(), 3u);
}

TEST(GameState, RefusesBadValuesAndKeepsItsLimits) {
  GameState state;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(state.set_number("x", 0, nan), GameStateError::NotFinite);
  EXPECT_EQ(state.set_number("x", 0, -inf), GameStateError::NotFinite);
  EXPECT_EQ(state.set_int("", 0, 1), GameStateError::EmptyName);
  EXPECT_EQ(state.set_int(std::string(GameState::kMaxNameBytes + 1, 'n'), 0, 1),
            GameStateError::NameTooLong);
  EXPECT_EQ(state.set_int(std::string(GameState::kMaxNameBytes, 'n'), 0, 1), GameStateError::None);
  EXPECT_EQ(state.start_timer("t", 0, 5, 5, 0), GameStateError::ZeroDelay);
  EXPECT_EQ(state.start_timer("t", 0, 5, 4, 0), GameStateError::ZeroDelay);
  EXPECT_EQ(state.size(), 1u) << "nothing refused was kept";
  for (std::uint64_t i = 1; i < GameState::kMaxEntries; ++i) {
    ASSERT_EQ(state.set_int("many", i, 1), GameStateError::None) << i;
  }
  EXPECT_EQ(state.size(), GameState::kMaxEntries);
  EXPECT_EQ(state.set_int("many", 0, 1), GameStateError::TooManyEntries);
  EXPECT_EQ(state.set_number("other", 0, 1.0), GameStateError::TooManyEntries);
  EXPECT_EQ(state.start_timer("other", 0, 0, 1, 0), GameStateError::TooManyEntries);
  EXPECT_EQ(state.set_int("many", 5, 9), GameStateError::None) << "a change is no new entry";
  EXPECT_EQ(state.get_int("many", 5), 9);
  EXPECT_FALSE(describe(GameStateError::TooManyEntries).empty());
}

TEST(GameState, TimersComeDueInTickThenKeyOrder) {
  GameState state;
  ASSERT_EQ(state.start_timer("b", 0, 0, 5, 0), GameStateError::None);
  ASSERT_EQ(state.start_timer("a", 1, 0, 5, 0), GameStateError::None);
  ASSERT_EQ(state.start_timer("a", 0, 0, 5, 3), GameStateError::None);
  ASSERT_EQ(state.start_timer("z", 0, 0, 4, 0), GameStateError::None);
  ASSERT_EQ(state.start_timer("later", 0, 0, 6, 0), GameStateError::None);
  const std::vector<GameKey> due = state.timers_due(5);
  const std::vector<GameKey> expected{{"z", 0}, {"a", 0}, {"a", 1}, {"b", 0}};
  EXPECT_EQ(due, expected);
  state.fired({"a", 0}, 5);
  state.fired({"b", 0}, 5);
  EXPECT_EQ(state.timer("a"), (GameTimer{8, 3})) << "periodic: due again 3 ticks on";
  EXPECT_FALSE(state.timer("b").has_value()) << "once: gone";
}

TEST(GameStateInWorld, AnEmptyGameStateLeavesTheHashAsItWas) {
  World world = small_world();
  const std::uint64_t bare = world.state_hash();
  world.game_state().set_int("score", 0, 1);
  const std::uint64_t with_score = world.state_hash();
  EXPECT_NE(with_score, bare);
  world.game_state().set_int("score", 0, 2);
  EXPECT_NE(world.state_hash(), with_score) << "the value is in the hash";
  world.game_state().set_int("score", 0, 1);
  world.game_state().set_int("score", 7, 1);
  EXPECT_NE(world.state_hash(), with_score) << "the index is in the hash";
  world.game_state().erase_int("score", 7);
  world.game_state().start_timer("score", 0, 0, 3, 0);
  EXPECT_NE(world.state_hash(), with_score) << "a timer is in the hash";
  world.game_state().clear();
  EXPECT_EQ(world.state_hash(), bare);
}

TEST(GameStateInWorld, SaveAndRestoreCarryIt) {
  World world = small_world();
  fill(world.game_state());
  for (int i = 0; i < 10; ++i) world.step(kDt);
  const SavedWorld saved = world.save();
  const std::uint64_t hash_at_save = world.state_hash();
  std::vector<std::uint64_t> first;
  for (int i = 0; i < 20; ++i) {
    world.game_state().set_int("score", 1, i);
    if (i == 5) world.game_state().cancel_timer("respawn", 2);
    world.step(kDt);
    first.push_back(world.state_hash());
  }
  world.restore(saved);
  EXPECT_EQ(world.state_hash(), hash_at_save);
  EXPECT_EQ(world.game_state().get_int("score", 1), 3);
  EXPECT_EQ(world.game_state().timer("respawn", 2), (GameTimer{15, 0}));
  for (int i = 0; i < 20; ++i) {
    world.game_state().set_int("score", 1, i);
    if (i == 5) world.game_state().cancel_timer("respawn", 2);
    world.step(kDt);
    EXPECT_EQ(world.state_hash(), first[static_cast<std::size_t>(i)]) << "step " << i;
  }
  World copy(saved);
  EXPECT_EQ(copy.state_hash(), hash_at_save);
}

TEST(GameStateInWorld, BytesCarryItToAFreshWorld) {
  World world = small_world();
  fill(world.game_state());
  for (int i = 0; i < 10; ++i) world.step(kDt);
  const std::vector<std::uint8_t> bytes = world.to_bytes();
  std::string error;
  std::optional<World> loaded = World::from_bytes(bytes, &error);
  ASSERT_TRUE(loaded.has_value()) << error;
  EXPECT_EQ(loaded->game_state(), world.game_state());
  EXPECT_EQ(loaded->state_hash(), world.state_hash());
  EXPECT_EQ(loaded->to_bytes(), bytes);
  for (int i = 0; i < 30; ++i) {
    world.step(kDt);
    loaded->step(kDt);
  }
  EXPECT_EQ(loaded->state_hash(), world.state_hash());
}

// Where the game state begins in a world's bytes: the bytes of the same world
// without it are exactly its prefix, less the three empty lists' counts.
std::size_t game_state_offset(World& world) {
  const GameState kept = world.game_state();
  world.game_state().clear();
  const std::size_t without = world.to_bytes().size();
  world.game_state() = kept;
  return without - 3 * 8;
}

std::string refused_because(const std::vector<std::uint8_t>& bytes) {
  std::string why;
  const std::optional<World> loaded = World::from_bytes(bytes, &why);
  return loaded ? std::string("accepted") : why;
}

TEST(GameStateInWorld, DamagedGameStateBytesAreRefusedWithAReason) {
  World world = small_world();
  fill(world.game_state());
  const std::vector<std::uint8_t> good = world.to_bytes();
  const std::size_t at = game_state_offset(world);
  ASSERT_EQ(good.size() - at, [&] {
    std::vector<std::uint8_t> own;
    world.game_state().append_bytes(own);
    return own.size();
  }());
  // Cut anywhere in the game state: refused.
  for (std::size_t n = at; n < good.size(); ++n) {
    const std::string why = refused_because({good.begin(), good.begin() + n});
    EXPECT_NE(why, "accepted") << n;
    EXPECT_NE(why.find("game state"), std::string::npos) << n << ": " << why;
  }
  // Layout: the integers' count, then ("score", 1): name length, name, index, value.
  std::uint64_t count = 0;
  std::memcpy(&count, good.data() + at, 8);
  ASSERT_EQ(count, 2u);
  std::vector<std::uint8_t> bytes = good;
  count = UINT64_MAX / 4;
  std::memcpy(bytes.data() + at, &count, 8);
  EXPECT_NE(refused_because(bytes).find("longer than the bytes left"), std::string::npos);
  bytes = good;
  const std::uint64_t long_name = GameState::kMaxNameBytes + 1;
  std::memcpy(bytes.data() + at + 8, &long_name, 8);
  EXPECT_NE(refused_because(bytes).find("over 64 bytes"), std::string::npos);
  bytes = good;
  const std::uint64_t no_name = 0;
  std::memcpy(bytes.data() + at + 8, &no_name, 8);
  EXPECT_NE(refused_because(bytes).find("empty"), std::string::npos);
  // The second integer's index (2) made 1: the same key twice.
  bytes = good;
  const std::size_t second = at + 8 + (8 + 5 + 8 + 8);
  const std::uint64_t one = 1;
  std::memcpy(bytes.data() + second + 8 + 5, &one, 8);
  EXPECT_NE(refused_because(bytes).find("out of order or repeated"), std::string::npos);
  // The number (after the two integers and its list's count) made NaN.
  bytes = good;
  const std::size_t number = second + (8 + 5 + 8 + 8) + 8 + (8 + 4 + 8);
  double value = 0.0;
  std::memcpy(&value, bytes.data() + number, 8);
  ASSERT_EQ(value, 0.125);
  value = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(bytes.data() + number, &value, 8);
  EXPECT_NE(refused_because(bytes).find("not finite"), std::string::npos);
  // Any bit of the game state flipped: refused, or read back as it was.
  for (std::size_t i = at; i < good.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      bytes = good;
      bytes[i] ^= static_cast<std::uint8_t>(1u << bit);
      std::string why;
      const std::optional<World> loaded = World::from_bytes(bytes, &why);
      if (loaded) {
        EXPECT_EQ(loaded->to_bytes(), bytes);
      } else {
        EXPECT_FALSE(why.empty());
      }
    }
  }
}

TEST(GameStateInWorld, TooManyEntriesInBytesAreRefused) {
  // Bytes claiming more than kMaxEntries entries, each well formed.
  std::vector<std::uint8_t> bytes;
  const auto put = [&bytes](std::uint64_t v) {
    const std::size_t at = bytes.size();
    bytes.resize(at + 8);
    std::memcpy(bytes.data() + at, &v, 8);
  };
  put(GameState::kMaxEntries + 1);
  for (std::uint64_t i = 0; i <= GameState::kMaxEntries; ++i) {
    put(1);
    bytes.push_back('k');
    put(i);
    put(0);
  }
  put(0);
  put(0);
  std::size_t used = 0;
  std::string error;
  EXPECT_FALSE(GameState::read_bytes(bytes, &used, &error).has_value());
  EXPECT_NE(error.find("over 4096 entries"), std::string::npos) << error;
}

}  // namespace
}  // namespace phys::testing
