// The game's variables and timers in the world (physics/game_state.h): their
// changes with the limits, the timers' schedule, their hash and their bytes.
#include "physics/game_state.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>

#include "physics/fnv_hash.h"

namespace phys {

std::string_view describe(GameStateError error) {
  switch (error) {
    case GameStateError::None:
      return "no error";
    case GameStateError::EmptyName:
      return "a game variable or timer needs a name";
    case GameStateError::NameTooLong:
      return "a game variable's or timer's name is over 64 bytes";
    case GameStateError::TooManyEntries:
      return "the game state holds 4096 variables and timers already";
    case GameStateError::NotFinite:
      return "a game number must be finite (not NaN or infinite)";
    case GameStateError::ZeroDelay:
      return "a timer must be due at a later tick than the current one";
  }
  return "unknown error";
}

namespace {

template <class Map>
auto find_in(const Map& map, std::string_view name, std::uint64_t index) {
  return map.find(GameState::KeyView{name, index});
}

// Sets `value` under the key, making the entry when it is new.
template <class Map, class Value>
void put(Map& map, std::string_view name, std::uint64_t index, const Value& value) {
  const auto it = map.find(GameState::KeyView{name, index});
  if (it != map.end()) {
    it->second = value;
  } else {
    map.emplace(GameKey{std::string(name), index}, value);
  }
}

template <class Map>
bool erase_from(Map& map, std::string_view name, std::uint64_t index) {
  const auto it = map.find(GameState::KeyView{name, index});
  if (it == map.end()) return false;
  map.erase(it);
  return true;
}

}  // namespace

std::optional<std::int64_t> GameState::get_int(std::string_view name, std::uint64_t index) const {
  const auto it = find_in(ints_, name, index);
  if (it == ints_.end()) return std::nullopt;
  return it->second;
}

std::optional<double> GameState::get_number(std::string_view name, std::uint64_t index) const {
  const auto it = find_in(numbers_, name, index);
  if (it == numbers_.end()) return std::nullopt;
  return it->second;
}

std::optional<GameTimer> GameState::timer(std::string_view name, std::uint64_t index) const {
  const auto it = find_in(timers_, name, index);
  if (it == timers_.end()) return std::nullopt;
  return it->second;
}

GameStateError GameState::check_new(std::string_view name, bool adds) const {
  if (name.empty()) return GameStateError::EmptyName;
  if (name.size() > kMaxNameBytes) return GameStateError::NameTooLong;
  if (adds && size() >= kMaxEntries) return GameStateError::TooManyEntries;
  return GameStateError::None;
}

GameStateError GameState::set_int(std::string_view name, std::uint64_t index, std::int64_t value) {
  const bool adds = find_in(ints_, name, index) == ints_.end();
  if (const GameStateError error = check_new(name, adds); error != GameStateError::None) {
    return error;
  }
  put(ints_, name, index, value);
  return GameStateError::None;
}

GameStateError GameState::set_number(std::string_view name, std::uint64_t index, double value) {
  if (!std::isfinite(value)) return GameStateError::NotFinite;
  const bool adds = find_in(numbers_, name, index) == numbers_.end();
  if (const GameStateError error = check_new(name, adds); error != GameStateError::None) {
    return error;
  }
  put(numbers_, name, index, value);
  return GameStateError::None;
}

GameStateError GameState::start_timer(std::string_view name, std::uint64_t index, std::uint64_t now,
                                      std::uint64_t due, std::uint64_t period) {
  if (due <= now) return GameStateError::ZeroDelay;
  const bool adds = find_in(timers_, name, index) == timers_.end();
  if (const GameStateError error = check_new(name, adds); error != GameStateError::None) {
    return error;
  }
  put(timers_, name, index, GameTimer{due, period});
  return GameStateError::None;
}

bool GameState::erase_int(std::string_view name, std::uint64_t index) {
  return erase_from(ints_, name, index);
}
bool GameState::erase_number(std::string_view name, std::uint64_t index) {
  return erase_from(numbers_, name, index);
}
bool GameState::cancel_timer(std::string_view name, std::uint64_t index) {
  return erase_from(timers_, name, index);
}

std::vector<GameKey> GameState::timers_due(std::uint64_t tick) const {
  std::vector<std::pair<std::uint64_t, const GameKey*>> due;
  for (const auto& [key, timer] : timers_) {
    if (timer.due <= tick) due.emplace_back(timer.due, &key);
  }
  // Keys are unique and already in (name, index) order: a stable sort by due keeps it.
  std::stable_sort(due.begin(), due.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<GameKey> keys;
  keys.reserve(due.size());
  for (const auto& [at, key] : due) keys.push_back(*key);
  return keys;
}

void GameState::fired(const GameKey& key, std::uint64_t tick) {
  const auto it = timers_.find(key);
  if (it == timers_.end()) return;
  if (it->second.period == 0 || it->second.period > UINT64_MAX - tick) {
    timers_.erase(it);
  } else {
    it->second.due = tick + it->second.period;
  }
}

void GameState::clear() {
  ints_.clear();
  numbers_.clear();
  timers_.clear();
}

namespace {

// A name as its length and its bytes, eight to a word (the last zero-padded).
void mix_key(Fnv1a64& hash, const GameKey& key) {
  hash.mix(key.name.size());
  for (std::size_t at = 0; at < key.name.size(); at += 8) {
    std::uint64_t word = 0;
    std::memcpy(&word, key.name.data() + at, std::min<std::size_t>(8, key.name.size() - at));
    hash.mix(word);
  }
  hash.mix(key.index);
}

}  // namespace

void GameState::mix_into(Fnv1a64& hash) const {
  // Each list's length first, so that entries cannot shift from one kind to another.
  hash.mix(ints_.size());
  for (const auto& [key, value] : ints_) {
    mix_key(hash, key);
    hash.mix(static_cast<std::uint64_t>(value));
  }
  hash.mix(numbers_.size());
  for (const auto& [key, value] : numbers_) {
    mix_key(hash, key);
    hash.mix_double(value);
  }
  hash.mix(timers_.size());
  for (const auto& [key, timer] : timers_) {
    mix_key(hash, key);
    hash.mix(timer.due);
    hash.mix(timer.period);
  }
}

std::size_t GameState::heap_bytes() const {
  // A map node: the key, the value and three pointers and a colour, roughly.
  constexpr std::size_t kNode = sizeof(GameKey) + 16 + 4 * sizeof(void*);
  std::size_t names = 0;
  const auto count_names = [&names](const auto& map) {
    for (const auto& entry : map) {
      if (entry.first.name.size() > 15) names += entry.first.name.capacity();
    }
  };
  count_names(ints_);
  count_names(numbers_);
  count_names(timers_);
  return size() * kNode + names;
}

}  // namespace phys
