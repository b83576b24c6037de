#pragma once
// The 2D world: bodies, and one fixed step at a time. It never reads a clock and
// knows nothing of networking; the caller gives it dt.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "physics/body.h"
#include "physics/contact_events.h"
#include "physics/crush_events.h"
#include "physics/game_state.h"
#include "physics/query.h"
#include "physics/sensor_events.h"
#include "physics/settings.h"
#include "physics/stats.h"

namespace phys {

class WorldImpl;
class World;

// A world's full state as a value (World::save): everything a step reads, so that
// restoring it and stepping gives, bit for bit, what the saved world would have
// given. Not the counters or the profile, which count work done, rolled back or not.
// Copyable; an empty SavedWorld holds nothing and cannot be restored.
class SavedWorld {
 public:
  SavedWorld();
  ~SavedWorld();
  SavedWorld(const SavedWorld& other);
  SavedWorld& operator=(const SavedWorld& other);
  SavedWorld(SavedWorld&&) noexcept;
  SavedWorld& operator=(SavedWorld&&) noexcept;

  bool empty() const { return impl_ == nullptr; }
  // The step count of the world when it was saved.
  std::uint64_t step_count() const;
  // Bytes the saved state holds on the heap (its arrays' capacity), for budgets.
  std::size_t bytes() const;

 private:
  friend class World;
  std::unique_ptr<WorldImpl> impl_;
};

class World {
 public:
  // The settings must pass check_settings (a programmer error otherwise).
  explicit World(const WorldSettings& settings = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  World(const World&) = delete;
  World& operator=(const World&) = delete;
  // A world in the saved state, with fresh counters (saved must not be empty).
  explicit World(const SavedWorld& saved);

  // Saved and restored state (SavedWorld says what it holds). save_into reuses the
  // target's arrays, so that saving every tick allocates nothing once they are
  // large enough; restore likewise reuses this world's. Rolling back N steps is
  // restore, then step N times. Contact events set on or off travel with the state.
  SavedWorld save() const;
  void save_into(SavedWorld& target) const;
  // `saved` must not be empty (a programmer error otherwise). The settings are
  // part of the state: afterwards they are the saved world's.
  void restore(const SavedWorld& saved);

  // The full state (what save() holds) as bytes, for a world in another process
  // built from the same core: a format tag and version, then each array with its
  // length, every number as its little-endian bit pattern. from_bytes checks the
  // tag, the version, every length and every body; nullopt and *error when the bytes
  // are not a world this core wrote. Not a stable interchange format: another
  // version of the core may refuse it.
  std::vector<std::uint8_t> to_bytes() const;
  static std::optional<World> from_bytes(std::span<const std::uint8_t> bytes,
                                         std::string* error = nullptr);

  // Adds a body; bodies may be added and removed between steps at any time.
  // Returns BodyId::invalid() and sets *error when the def is refused.
  BodyId add_body(const BodyDef& def, BodyDefError* error = nullptr);
  // Returns false for an unknown or stale id.
  bool remove_body(BodyId id);
  bool contains(BodyId id) const;

  // The input of a dynamic body (not a kinematic one): held until set again. Non-finite values are
  // refused (false); the magnitude is clamped to settings().max_acceleration.
  bool set_acceleration(BodyId id, Vec2 acceleration);
  // Teleports or kicks a body (tools, tests); wakes it. False for bad ids or values.
  // A kinematic body is moved by its velocity: set it (or its position) each step to
  // lead it along a path. Positions set by hand teleport: only a velocity pushes and
  // carries what is in the way. False for a static body.
  bool set_position(BodyId id, Vec2 position);
  bool set_velocity(BodyId id, Vec2 velocity);

  // The alive body with this name and the lowest id index (names need not be
  // unique); nothing for an empty or unknown name. A binary search over the named
  // bodies.
  std::optional<BodyId> find_body(std::string_view name) const;
  // Its name ("" for an unnamed body or a bad id). Valid until the body is removed.
  std::string_view name(BodyId id) const;
  // Its collision filter (nothing for a bad id). Setting one wakes the body and
  // what touches it, and has the pairs found anew at the next step.
  std::optional<Filter> filter(BodyId id) const;
  bool set_filter(BodyId id, const Filter& filter);
  bool is_sensor(BodyId id) const;

  std::optional<BodyState> body(BodyId id) const;
  // Every body, in ascending id order (the order the state hash uses).
  std::vector<BodyState> bodies() const;
  void for_each_body(const std::function<void(const BodyState&)>& visit) const;
  std::size_t body_count() const;
  std::size_t dynamic_body_count() const;
  std::size_t awake_body_count() const;

  // One fixed step of dt seconds (dt finite and > 0; a programmer error otherwise).
  void step(double dt);

  // 64-bit hash of every body's id, shape, motion, position, velocity, acceleration
  // and size, and its filter and sensor flag where not the default, in id order,
  // over the exact bit patterns, then the game state when it is not empty (every
  // variable and timer in key order). Equal states give equal hashes. Names are not
  // in it.
  std::uint64_t state_hash() const;

  // The game's variables and timers (physics/game_state.h): part of the world's
  // state, so save, restore, to_bytes, from_bytes and the state hash carry them.
  // The world itself never reads or changes them; game rules do.
  GameState& game_state();
  const GameState& game_state() const;

  // Steps taken since creation.
  std::uint64_t step_count() const;

  // Contact events (physics/contact_events.h says what a contact is). Off by
  // default, and then the step does no work for them at all (the counters
  // contact_pair_tests and contact_events stay put). On, each sub-step tests its
  // candidate pairs once more, and each step sorts the touches it found: +15% to
  // +20% of a step in a rain or a pile of 4,000 bodies (docs/BENCHMARKS.md). Events
  // change nothing in the simulation: the state and its hash are the same on or
  // off. A change from off to on or back forgets every contact tracked so far.
  void set_contact_events(bool on);
  bool contact_events_on() const;
  // The last step's begins and ends, ordered by (a, b) ids; empty while off.
  const std::vector<ContactEvent>& contact_events() const;
  // Pairs in contact after the last step (while on).
  std::size_t contacts_in_touch() const;

  // Sensor events (physics/sensor_events.h says what an overlap is): the last
  // step's begins and ends, ordered by (sensor, visitor) ids. Always on: a world
  // without sensors does no work for them.
  const std::vector<SensorEvent>& sensor_events() const;
  // (Sensor, visitor) pairs overlapping after the last step.
  std::size_t sensor_overlaps() const;

  // Crush events (physics/crush_events.h says when a body is pinned): the last
  // step's (kinematic, dynamic, static) triples, each once, ordered by their ids.
  // A world without kinematic bodies does no work for them.
  const std::vector<CrushEvent>& crush_events() const;

  // Queries (physics/query.h says exactly what each finds, how bad input is refused
  // and what they cost). Const, and each returns its answer by value: rules may add
  // or remove bodies while going through it. Not to be called from several threads
  // at once: the first query after a change files the bodies in grids.
  // The first body a ray from `origin` along `translation` meets, or all it meets
  // (by fraction, then id).
  std::optional<CastHit> cast_ray(Vec2 origin, Vec2 translation, const QueryFilter& filter = {},
                                  QueryError* error = nullptr) const;
  std::vector<CastHit> cast_ray_all(Vec2 origin, Vec2 translation, const QueryFilter& filter = {},
                                    QueryError* error = nullptr) const;
  // The bodies overlapping a box, a circle or a point, ascending id.
  std::vector<BodyId> overlap_box(const Aabb& box, const QueryFilter& filter = {},
                                  QueryError* error = nullptr) const;
  std::vector<BodyId> overlap_circle(Vec2 center, double radius, const QueryFilter& filter = {},
                                     QueryError* error = nullptr) const;
  std::vector<BodyId> overlap_point(Vec2 point, const QueryFilter& filter = {},
                                    QueryError* error = nullptr) const;
  // The first body a circle or a box moved from `center` along `translation` meets.
  std::optional<CastHit> cast_circle(Vec2 center, double radius, Vec2 translation,
                                     const QueryFilter& filter = {},
                                     QueryError* error = nullptr) const;
  std::optional<CastHit> cast_box(Vec2 center, Vec2 half_extents, Vec2 translation,
                                  const QueryFilter& filter = {},
                                  QueryError* error = nullptr) const;

  const WorldSettings& settings() const;
  const StageCounters& counters() const;
  const StepProfile& last_profile() const;

 private:
  // The core's white-box tests (tests/unit) read the step's state through it.
  friend struct WorldInternals;
  std::unique_ptr<WorldImpl> impl_;
};

}  // namespace phys
