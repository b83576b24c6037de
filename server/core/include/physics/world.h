#pragma once
// The 2D world: bodies, and one fixed step at a time. It never reads a clock and
// knows nothing of networking; the caller gives it dt.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "physics/body.h"
#include "physics/contact_events.h"
#include "physics/sensor_events.h"
#include "physics/settings.h"
#include "physics/stats.h"

namespace phys {

class WorldImpl;

class World {
 public:
  // The settings must pass check_settings (a programmer error otherwise).
  explicit World(const WorldSettings& settings = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  World(const World&) = delete;
  World& operator=(const World&) = delete;

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
  // over the exact bit patterns. Equal states give equal hashes. Names are not in it.
  std::uint64_t state_hash() const;
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

  const WorldSettings& settings() const;
  const StageCounters& counters() const;
  const StepProfile& last_profile() const;

 private:
  std::unique_ptr<WorldImpl> impl_;
};

}  // namespace phys
