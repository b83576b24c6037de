// GameState::append_bytes and read_bytes: the game state inside World::to_bytes.
// Three counted lists (integers, numbers, timers), each entry its key (name length,
// name, index) and its value, every number as its little-endian bit pattern. The
// reader trusts nothing: every length against the bytes left and the limits, every
// key after the one before it, every number finite.
#include <cmath>
#include <cstring>
#include <type_traits>

#include "physics/game_state.h"

namespace phys {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "game state bytes are little-endian bit patterns");

namespace {

// The fewest bytes an entry takes: the name's length, one byte of name, the index,
// then its value (8 bytes; a timer's two, 16).
constexpr std::size_t kKeyBytes = 8 + 1 + 8;

template <class T>
void put(std::vector<std::uint8_t>& out, T value) {
  static_assert(std::is_arithmetic_v<T>);
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &value, sizeof(T));
}

void put_key(std::vector<std::uint8_t>& out, const GameKey& key) {
  put<std::uint64_t>(out, key.name.size());
  out.insert(out.end(), key.name.begin(), key.name.end());
  put<std::uint64_t>(out, key.index);
}

class Bytes {
 public:
  explicit Bytes(std::span<const std::uint8_t> in) : in_(in) {}
  template <class T>
  bool take(T& value) {
    if (!ok() || in_.size() - at_ < sizeof(T)) return fail("the bytes end in the middle of it");
    std::memcpy(&value, in_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  // A list's length: refused when the bytes left could not hold it.
  bool take_count(std::size_t& n, std::size_t entry_bytes) {
    std::uint64_t wide = 0;
    if (!take(wide)) return false;
    if (wide > (in_.size() - at_) / entry_bytes) {
      return fail("a list's length is longer than the bytes left");
    }
    n = static_cast<std::size_t>(wide);
    return true;
  }
  // A key, which must come after `previous` (when there is one).
  bool take_key(GameKey& key, const GameKey* previous) {
    std::uint64_t length = 0;
    if (!take(length)) return false;
    if (length == 0) return fail("a name is empty");
    if (length > GameState::kMaxNameBytes) return fail("a name is over 64 bytes");
    if (in_.size() - at_ < length) return fail("the bytes end in the middle of a name");
    // At most kMaxNameBytes here, so it fits a size_t on every platform (wasm32 too).
    const auto bytes = static_cast<std::size_t>(length);
    key.name.assign(reinterpret_cast<const char*>(in_.data() + at_), bytes);
    at_ += bytes;
    if (!take(key.index)) return false;
    if (previous && !(*previous < key)) return fail("its keys are out of order or repeated");
    return true;
  }
  bool fail(std::string why) {
    if (problem.empty()) problem = std::move(why);
    return false;
  }
  bool ok() const { return problem.empty(); }
  std::size_t used() const { return at_; }
  std::string problem;

 private:
  std::span<const std::uint8_t> in_;
  std::size_t at_ = 0;
};

// One list: its count, then each entry's key and `read_value` of it.
template <class Map, class ReadValue>
bool read_list(Bytes& bytes, Map& map, std::size_t value_bytes, std::size_t& entries,
               ReadValue read_value) {
  std::size_t n = 0;
  if (!bytes.take_count(n, kKeyBytes + value_bytes)) return false;
  entries += n;
  if (entries > GameState::kMaxEntries) return bytes.fail("it holds over 4096 entries");
  const GameKey* previous = nullptr;
  for (std::size_t i = 0; i < n; ++i) {
    GameKey key;
    typename Map::mapped_type value{};
    if (!bytes.take_key(key, previous) || !read_value(value)) return false;
    previous = &map.emplace_hint(map.end(), std::move(key), value)->first;
  }
  return true;
}

}  // namespace

void GameState::append_bytes(std::vector<std::uint8_t>& out) const {
  put<std::uint64_t>(out, ints_.size());
  for (const auto& [key, value] : ints_) {
    put_key(out, key);
    put(out, value);
  }
  put<std::uint64_t>(out, numbers_.size());
  for (const auto& [key, value] : numbers_) {
    put_key(out, key);
    put(out, value);
  }
  put<std::uint64_t>(out, timers_.size());
  for (const auto& [key, timer] : timers_) {
    put_key(out, key);
    put(out, timer.due);
    put(out, timer.period);
  }
}

std::optional<GameState> GameState::read_bytes(std::span<const std::uint8_t> in, std::size_t* used,
                                               std::string* error) {
  Bytes bytes(in);
  GameState state;
  std::size_t entries = 0;
  const bool read =
      read_list(bytes, state.ints_, 8, entries, [&](std::int64_t& v) { return bytes.take(v); }) &&
      read_list(bytes, state.numbers_, 8, entries,
                [&](double& v) {
                  if (!bytes.take(v)) return false;
                  return std::isfinite(v) || bytes.fail("a number is not finite");
                }) &&
      read_list(bytes, state.timers_, 16, entries,
                [&](GameTimer& t) { return bytes.take(t.due) && bytes.take(t.period); });
  if (!read) {
    if (error) *error = "its game state: " + bytes.problem;
    return std::nullopt;
  }
  if (used) *used = bytes.used();
  return state;
}

}  // namespace phys
