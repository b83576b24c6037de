// World::to_bytes and World::from_bytes: the state World::save copies, as bytes.
// One function, state_fields, names every field once, in order; the writer and
// the reader both walk it, so that the two cannot disagree. Numbers are written as
// their little-endian bit patterns (every platform the core is built for is
// little-endian: checked at compile time). The grid of static and sleeping bodies
// is not written: it is built from their boxes, as the world builds it.
// What the reader checks before it trusts the state is world_bytes_check.cpp's.
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include "world_impl.h"

namespace phys {

// Compilers' own macro rather than std::endian, which not every standard library
// the core is built with (emscripten's) has.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "world bytes are little-endian bit patterns");

namespace {

constexpr char kTag[8] = {'p', 'h', 'y', 's', 'w', 'r', 'l', 'd'};
constexpr std::uint32_t kVersion = 2;  // 2: the game state at the end

class Writer {
 public:
  static constexpr bool kReading = false;
  template <class T>
  void number(T& value) {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    const std::size_t at = out.size();
    out.resize(at + sizeof(T));
    std::memcpy(out.data() + at, &value, sizeof(T));
  }
  // A count of elements of at least `element_bytes` bytes each.
  void count(std::size_t& n, std::size_t /*element_bytes*/) {
    std::uint64_t wide = n;
    number(wide);
  }
  bool ok() const { return true; }
  void fail(const std::string& /*why*/) {}
  void game_state(GameState& state) { state.append_bytes(out); }
  std::vector<std::uint8_t> out;
};

class Reader {
 public:
  static constexpr bool kReading = true;
  explicit Reader(std::span<const std::uint8_t> bytes) : in_(bytes) {}
  template <class T>
  void number(T& value) {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    if (!take(sizeof(T))) {
      value = T{};
      return;
    }
    if constexpr (std::is_same_v<T, bool>) {
      // Any byte but 0 or 1 is no bool: copied into one, it would be undefined.
      const std::uint8_t byte = in_[at_ - 1];
      if (byte > 1) fail("a flag is neither 0 nor 1");
      value = byte == 1;
    } else {
      std::memcpy(&value, in_.data() + at_ - sizeof(T), sizeof(T));
    }
  }
  // Refuses a count that the bytes left could not hold, so that a lying length
  // cannot make the reader allocate more than the message's own size.
  void count(std::size_t& n, std::size_t element_bytes) {
    std::uint64_t wide = 0;
    number(wide);
    if (!ok_) return;
    if (wide > (in_.size() - at_) / element_bytes) {
      fail("an array's length is longer than the bytes left");
      n = 0;
      return;
    }
    n = static_cast<std::size_t>(wide);
  }
  bool ok() const { return ok_; }
  void fail(std::string why) {
    if (ok_) problem = std::move(why);
    ok_ = false;
  }
  bool at_end() const { return at_ == in_.size(); }
  // GameState::read_bytes checks its own part of the bytes.
  void game_state(GameState& state) {
    if (!ok_) return;
    std::size_t used = 0;
    std::string why;
    std::optional<GameState> read = GameState::read_bytes(in_.subspan(at_), &used, &why);
    if (!read) return fail(why);
    state = std::move(*read);
    at_ += used;
  }
  std::string problem;

 private:
  bool take(std::size_t n) {
    if (!ok_) return false;
    if (in_.size() - at_ < n) {
      fail("the bytes end in the middle of the state");
      return false;
    }
    at_ += n;
    return true;
  }
  std::span<const std::uint8_t> in_;
  std::size_t at_ = 0;
  bool ok_ = true;
};

template <class A>
void field(A& a, Vec2& v) {
  a.number(v.x);
  a.number(v.y);
}
template <class A>
void field(A& a, Aabb& box) {
  field(a, box.min);
  field(a, box.max);
}
template <class A, class T>
requires(std::is_arithmetic_v<T> || std::is_enum_v<T>) &&
    (!std::is_same_v<T, std::size_t>)void field(A& a, T& value) {
  a.number(value);
}
// A size_t is 64 bits here and 32 in WebAssembly: always 64 in the bytes.
template <class A>
void field(A& a, std::size_t& value) {
  std::uint64_t wide = value;
  a.number(wide);
  if constexpr (A::kReading) {
    if (wide > SIZE_MAX) a.fail("a count does not fit this platform");
    value = static_cast<std::size_t>(wide);
  }
}

// A vector: its length, then each element through `each`. `element_bytes` is the
// fewest bytes an element takes in the stream.
template <class A, class T, class Each>
void array(A& a, std::vector<T>& v, std::size_t element_bytes, Each each) {
  std::size_t n = v.size();
  a.count(n, element_bytes);
  if constexpr (A::kReading) v.assign(n, T{});
  for (std::size_t i = 0; i < n && a.ok(); ++i) each(v[i]);
}
template <class A, class T>
void numbers(A& a, std::vector<T>& v) {
  array(a, v, sizeof(T), [&](T& x) { field(a, x); });
}

// A string: its length, then its bytes.
template <class A>
void text(A& a, std::string& s) {
  std::size_t n = s.size();
  a.count(n, 1);
  if constexpr (A::kReading) s.assign(n, '\0');
  for (std::size_t i = 0; i < n && a.ok(); ++i) a.number(s[i]);
}

template <class A>
void settings_fields(A& a, WorldSettings& s) {
  field(a, s.gravity);
  field(a, s.integrator);
  field(a, s.substeps);
  field(a, s.slop);
  field(a, s.position_iterations);
  field(a, s.velocity_iterations);
  field(a, s.warm_starting);
  field(a, s.continuous);
  field(a, s.shock_propagation);
  field(a, s.hold_resting_support);
  field(a, s.rest_speed);
  field(a, s.max_speed);
  field(a, s.max_acceleration);
  field(a, s.sleeping);
  field(a, s.sleep_speed);
  field(a, s.sleep_time);
  field(a, s.has_bounds);
  field(a, s.bounds);
  field(a, s.max_body_size);
  field(a, s.max_bodies);
  field(a, s.simd_contact_lanes);
  field(a, s.relaxed_position_passes);
  field(a, s.profile);
}

template <class A>
void body_fields(A& a, Body& b) {
  field(a, b.position);
  field(a, b.half);
  field(a, b.velocity);
  field(a, b.radius);
  field(a, b.inv_mass);
  field(a, b.correction);
  field(a, b.shape);
  field(a, b.motion);
  field(a, b.alive);
  field(a, b.awake);
  field(a, b.generation);
  field(a, b.restitution);
  field(a, b.contact_friction);
  field(a, b.load);
  field(a, b.acceleration);
  field(a, b.mass);
  field(a, b.friction);
  field(a, b.still_time);
  field(a, b.held);
  field(a, b.still_anchor);
}
// 8 vectors, 7 numbers, 4 one-byte fields and the generation.
constexpr std::size_t kBodyBytes = 8 * 16 + 7 * 8 + 4 + 4;

template <class A>
void warm_entry_fields(A& a, WarmEntry& e) {
  field(a, e.partner);
  field(a, e.generation);
  field(a, e.impulse);
  field(a, e.tangent_impulse);
}
constexpr std::size_t kWarmEntryBytes = 4 + 4 + 8 + 8;

}  // namespace

// Every field of the state World::save copies, in the order of the bytes.
template <class A>
void state_fields(A& a, WorldImpl& w) {
  settings_fields(a, w.settings);
  field(a, w.steps);
  array(a, w.bodies, kBodyBytes, [&](Body& b) { body_fields(a, b); });
  field(a, w.contact_events_on);
  w.contact_tracker.state_fields(a);
  numbers(a, w.warm_count);
  numbers(a, w.warm_first);
  // A slot's own entries (a sleeping body's) only as many as it counts: the rest
  // are never read, and most bodies keep theirs in the pool.
  if (w.warm_first.size() != w.warm_count.size()) {
    a.fail("its warm-start arrays do not have one entry per body slot");
  }
  if constexpr (A::kReading) w.warm.assign(w.warm_count.size(), WarmImpulses{});
  for (std::size_t slot = 0; slot < w.warm_count.size() && a.ok(); ++slot) {
    if (w.warm_first[slot] != kWarmInSlot) continue;
    if (w.warm_count[slot] > kWarmSlots) {
      a.fail("a body has more warm-start entries than slots");
      break;
    }
    for (std::uint8_t i = 0; i < w.warm_count[slot]; ++i) {
      warm_entry_fields(a, w.warm[slot].entries[i]);
    }
  }
  array(a, w.warm_pool, kWarmEntryBytes, [&](WarmEntry& e) { warm_entry_fields(a, e); });
  numbers(a, w.lists.active);
  field(a, w.lists.joined);
  numbers(a, w.lists.fixed);
  array(a, w.lists.fixed_boxes, 32, [&](Aabb& box) { field(a, box); });
  field(a, w.lists.fixed_circles);
  field(a, w.lists.fixed_sleeping);
  array(a, w.candidates.list, 17, [&](Candidate& c) {
    field(a, c.lower);
    field(a, c.upper);
    field(a, c.lower_pos);
    field(a, c.upper_pos);
    field(a, c.fixed);
  });
  numbers(a, w.candidates.first);
  array(a, w.candidates.fat_boxes, 32, [&](Aabb& box) { field(a, box); });
  field(a, w.candidates.valid);
  numbers(a, w.free_slots_);
  field(a, w.alive_count_);
  field(a, w.dynamic_count_);
  field(a, w.lists_dirty_);
  field(a, w.rebuild_all_);
  numbers(a, w.changed_slots_);
  // The vocabulary: filters, names, sensors and kinematic bodies.
  array(a, w.filters, 13, [&](BodyFilter& f) {
    field(a, f.filter.category_bits);
    field(a, f.filter.mask_bits);
    field(a, f.filter.group);
    field(a, f.sensor);
  });
  array(a, w.names, 8, [&](std::string& name) { text(a, name); });
  array(a, w.name_index, 12, [&](std::pair<std::string, std::uint32_t>& entry) {
    text(a, entry.first);
    field(a, entry.second);
  });
  numbers(a, w.sensors);
  w.sensor_tracker.state_fields(a);
  numbers(a, w.lists.kinematic);
  field(a, w.kinematic_count_);
  field(a, w.filtered_count_);
  a.game_state(w.game_state);
}

template <class A>
void SensorTracker::state_fields(A& a) {
  array(a, current_, 16, [&](Pair& p) {
    field(a, p.sensor);
    field(a, p.sensor_generation);
    field(a, p.visitor);
    field(a, p.visitor_generation);
  });
}

template <class A>
void ContactTracker::state_fields(A& a) {
  array(a, current_, 8 + 4 + 4 + 32, [&](Contacting& c) {
    field(a, c.pair.slots);
    field(a, c.pair.generation_a);
    field(a, c.pair.generation_b);
    field(a, c.point);
    field(a, c.normal);
  });
  numbers(a, stepped_);
  field(a, serial_);
  numbers(a, removed_flag_);
  numbers(a, removed_);
}

std::vector<std::uint8_t> World::to_bytes() const {
  Writer writer;
  writer.out.reserve(4096 + impl_->state_bytes());
  writer.out.assign(std::begin(kTag), std::end(kTag));
  std::uint32_t version = kVersion;
  writer.number(version);
  state_fields(writer, *impl_);
  return std::move(writer.out);
}

std::optional<World> World::from_bytes(std::span<const std::uint8_t> bytes, std::string* error) {
  const auto refuse = [&](const std::string& why) -> std::optional<World> {
    if (error) *error = "not a world's state: " + why;
    return std::nullopt;
  };
  if (bytes.size() < sizeof(kTag) + 4 || std::memcmp(bytes.data(), kTag, sizeof(kTag)) != 0) {
    return refuse("the bytes do not begin with the world tag");
  }
  Reader reader(bytes.subspan(sizeof(kTag)));
  std::uint32_t version = 0;
  reader.number(version);
  if (version != kVersion) {
    return refuse("format version " + std::to_string(version) + ", this core reads " +
                  std::to_string(kVersion));
  }
  World world;
  state_fields(reader, *world.impl_);
  if (!reader.ok()) return refuse(reader.problem);
  if (!reader.at_end()) return refuse("bytes are left over after the state");
  if (std::string problem = check_read_state(*world.impl_); !problem.empty()) {
    return refuse(problem);
  }
  world.impl_->lists.fixed_grid.build(world.impl_->lists.fixed_boxes);
  return world;
}

}  // namespace phys
