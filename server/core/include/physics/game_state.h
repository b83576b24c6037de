#pragma once
// A game's own state, kept in the world beside the bodies (World::game_state): typed
// variables and timers, each named by a key (name, index). Because it lives in the
// world, whatever carries a world carries it: World::save and restore, to_bytes and
// from_bytes (so a Welcome's world_state and a resync), and the state hash (only
// when it holds something, so that a world without game state hashes as before).
//
// Everything is held in ordered containers and visited in key order, so that the
// hash and the bytes are the same on every platform. Integers, numbers and timers
// are three separate sets of keys: an integer "score" and a timer "score" are two
// entries.
#include <compare>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace phys {

class Fnv1a64;

// A variable's or a timer's name and index: the index lets a game keep one per
// player or per body under one name. Ordered by name, then index.
struct GameKey {
  std::string name;
  std::uint64_t index = 0;
  // Written out rather than defaulted with <=>: the libc++ of Debian's emscripten
  // has no three-way comparison for std::string.
  bool operator<(const GameKey& other) const {
    const int by_name = name.compare(other.name);
    return by_name != 0 ? by_name < 0 : index < other.index;
  }
  bool operator==(const GameKey&) const = default;
};

// A timer: due at a tick, then again every `period` ticks (0: once).
struct GameTimer {
  std::uint64_t due = 0;
  std::uint64_t period = 0;
  bool operator==(const GameTimer&) const = default;
};

// Why a change was refused (nothing changes then).
enum class GameStateError : std::uint8_t {
  None,
  EmptyName,       // a name of no characters
  NameTooLong,     // over GameState::kMaxNameBytes
  TooManyEntries,  // a new entry beyond GameState::kMaxEntries
  NotFinite,       // a number that is NaN or infinite
  ZeroDelay,       // a timer due now or in the past: it must be due at a later tick
};
// A sentence saying why, for logs and errors.
std::string_view describe(GameStateError error);

class GameState {
 public:
  // Limits against a game (or a peer's bytes) that grows the state without bound:
  // the entries of all three kinds together, and a name's bytes.
  static constexpr std::size_t kMaxEntries = 4096;
  static constexpr std::size_t kMaxNameBytes = 64;

  // Compares a key with a (name, index) without making a string.
  struct KeyLess {
    using is_transparent = void;
    template <class A, class B>
    bool operator()(const A& a, const B& b) const {
      const std::string_view left = a.name;
      const std::string_view right = b.name;
      return left != right ? left < right : a.index < b.index;
    }
  };
  struct KeyView {
    std::string_view name;
    std::uint64_t index = 0;
  };

  std::optional<std::int64_t> get_int(std::string_view name, std::uint64_t index = 0) const;
  std::optional<double> get_number(std::string_view name, std::uint64_t index = 0) const;
  std::optional<GameTimer> timer(std::string_view name, std::uint64_t index = 0) const;

  GameStateError set_int(std::string_view name, std::uint64_t index, std::int64_t value);
  GameStateError set_number(std::string_view name, std::uint64_t index, double value);
  // Starts (or starts again) a timer due at `due`, which must be after `now`.
  GameStateError start_timer(std::string_view name, std::uint64_t index, std::uint64_t now,
                             std::uint64_t due, std::uint64_t period);
  // Each true when there was one to remove.
  bool erase_int(std::string_view name, std::uint64_t index = 0);
  bool erase_number(std::string_view name, std::uint64_t index = 0);
  bool cancel_timer(std::string_view name, std::uint64_t index = 0);

  // The timers due at or before `tick`, in (due tick, name, index) order.
  std::vector<GameKey> timers_due(std::uint64_t tick) const;
  // A timer that fires at `tick`: started again `period` ticks on, or removed.
  void fired(const GameKey& key, std::uint64_t tick);

  bool empty() const { return ints_.empty() && numbers_.empty() && timers_.empty(); }
  std::size_t size() const { return ints_.size() + numbers_.size() + timers_.size(); }
  void clear();
  const std::map<GameKey, std::int64_t, KeyLess>& ints() const { return ints_; }
  const std::map<GameKey, double, KeyLess>& numbers() const { return numbers_; }
  const std::map<GameKey, GameTimer, KeyLess>& timers() const { return timers_; }

  // Every entry, in key order, into the world's state hash.
  void mix_into(Fnv1a64& hash) const;
  // Heap bytes held, roughly (for SavedWorld::bytes).
  std::size_t heap_bytes() const;

  // The state as bytes (three counted lists of entries, little-endian), appended.
  void append_bytes(std::vector<std::uint8_t>& out) const;
  // Reads what append_bytes wrote from the start of `in`; *used: the bytes read.
  // nullopt and *error when the bytes are not a game state: a length beyond the
  // bytes, a name empty or too long, keys out of order or repeated, a number not
  // finite, more than kMaxEntries entries.
  static std::optional<GameState> read_bytes(std::span<const std::uint8_t> in, std::size_t* used,
                                             std::string* error);

  bool operator==(const GameState&) const = default;

 private:
  // EmptyName, NameTooLong, TooManyEntries (when `adds` a new entry), or None.
  GameStateError check_new(std::string_view name, bool adds) const;

  std::map<GameKey, std::int64_t, KeyLess> ints_;
  std::map<GameKey, double, KeyLess> numbers_;
  std::map<GameKey, GameTimer, KeyLess> timers_;
};

}  // namespace phys
