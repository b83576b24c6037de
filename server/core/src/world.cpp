// World and SavedWorld, the public face: each call checks its arguments and hands
// on to WorldImpl (world_bodies.cpp, the step in step.cpp).
#include "physics/world.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "world_impl.h"
#include "world_limits.h"

namespace phys {

World::World(const WorldSettings& settings) : impl_(std::make_unique<WorldImpl>(settings)) {}
World::~World() = default;
World::World(World&&) noexcept = default;

World::World(const SavedWorld& saved) : impl_(std::make_unique<WorldImpl>(*saved.impl_)) {
  assert(!saved.empty());
  impl_->counters = {};
  impl_->profile = {};
}

SavedWorld World::save() const {
  SavedWorld saved;
  save_into(saved);
  return saved;
}

void World::save_into(SavedWorld& target) const {
  if (target.impl_) {
    *target.impl_ = *impl_;  // reuses the target's arrays
  } else {
    target.impl_ = std::make_unique<WorldImpl>(*impl_);
  }
}

void World::restore(const SavedWorld& saved) {
  assert(!saved.empty());
  // The counters and the profile count the work done, steps rolled back included.
  StageCounters counters = impl_->counters;
  StepProfile profile = impl_->profile;
  *impl_ = *saved.impl_;
  impl_->counters = counters;
  impl_->profile = profile;
}

// ---- SavedWorld ----

SavedWorld::SavedWorld() = default;
SavedWorld::~SavedWorld() = default;
SavedWorld::SavedWorld(SavedWorld&&) noexcept = default;
SavedWorld& SavedWorld::operator=(SavedWorld&&) noexcept = default;
SavedWorld::SavedWorld(const SavedWorld& other)
    : impl_(other.impl_ ? std::make_unique<WorldImpl>(*other.impl_) : nullptr) {}
SavedWorld& SavedWorld::operator=(const SavedWorld& other) {
  if (this == &other) return *this;
  if (!other.impl_) {
    impl_.reset();
  } else if (impl_) {
    *impl_ = *other.impl_;
  } else {
    impl_ = std::make_unique<WorldImpl>(*other.impl_);
  }
  return *this;
}

std::uint64_t SavedWorld::step_count() const { return impl_ ? impl_->steps : 0; }

std::size_t SavedWorld::bytes() const { return impl_ ? impl_->state_bytes() : 0; }
World& World::operator=(World&&) noexcept = default;

BodyId World::add_body(const BodyDef& def, BodyDefError* error) {
  return impl_->add_body(def, error);
}
bool World::remove_body(BodyId id) { return impl_->remove_body(id); }
bool World::contains(BodyId id) const { return impl_->find(id) != nullptr; }

bool World::set_acceleration(BodyId id, Vec2 acceleration) {
  Body* b = impl_->find(id);
  if (!b || !b->is_dynamic() || !is_finite(acceleration)) return false;
  acceleration = clamp_counted(acceleration, impl_->settings.max_acceleration,
                               impl_->counters.acceleration_clamps);
  if (acceleration == b->acceleration) return true;
  b->acceleration = acceleration;
  impl_->wake(id.index);
  return true;
}

bool World::set_position(BodyId id, Vec2 position) {
  Body* b = impl_->find(id);
  if (!b || !within_coordinate_limit(position)) return false;
  if (b->motion == Motion::Kinematic) {
    // A kinematic body led along a path by hand wakes what sleeps where it goes.
    const Vec2 margin{2.0 * impl_->settings.slop, 2.0 * impl_->settings.slop};
    const Vec2 low{std::min(b->position.x, position.x), std::min(b->position.y, position.y)};
    const Vec2 high{std::max(b->position.x, position.x), std::max(b->position.y, position.y)};
    impl_->wake_in({low - b->half - margin, high + b->half + margin}, id.index);
  }
  b->position = position;
  b->still_time = 0.0;
  if (b->motion == Motion::Static) impl_->query_index.forget_static();
  impl_->query_index.forget_moving();  // and wake, below, the sleeping ones if it slept
  impl_->wake(id.index);
  impl_->lists_dirty_ = true;
  impl_->rebuild_all_ = true;  // a static or sleeping body's box moved
  return true;
}

bool World::set_velocity(BodyId id, Vec2 velocity) {
  Body* b = impl_->find(id);
  if (!b || b->motion == Motion::Static || !is_finite(velocity)) return false;
  velocity = clamp_counted(velocity, impl_->settings.max_speed, impl_->counters.speed_clamps);
  b->velocity = velocity;
  impl_->wake(id.index);
  return true;
}

std::optional<BodyState> World::body(BodyId id) const {
  if (!impl_->find(id)) return std::nullopt;
  return impl_->state_of(id.index);
}

std::vector<BodyState> World::bodies() const {
  std::vector<BodyState> out;
  out.reserve(impl_->bodies.size());
  for_each_body([&out](const BodyState& s) { out.push_back(s); });
  return out;
}

void World::for_each_body(const std::function<void(const BodyState&)>& visit) const {
  for (std::uint32_t i = 0; i < impl_->bodies.size(); ++i) {
    if (impl_->bodies[i].alive) visit(impl_->state_of(i));
  }
}

std::optional<BodyId> World::find_body(std::string_view name) const {
  if (name.empty()) return std::nullopt;
  const std::uint32_t slot = impl_->find_name(name);
  if (slot == WorldImpl::kNoSlot) return std::nullopt;
  return BodyId{slot, impl_->bodies[slot].generation};
}

std::string_view World::name(BodyId id) const {
  if (!impl_->find(id)) return {};
  return impl_->names[id.index];
}

std::optional<Filter> World::filter(BodyId id) const {
  if (!impl_->find(id)) return std::nullopt;
  return impl_->filters[id.index].filter;
}

bool World::set_filter(BodyId id, const Filter& filter) {
  if (!impl_->find(id)) return false;
  impl_->set_filter(id.index, filter);
  return true;
}

bool World::is_sensor(BodyId id) const {
  return impl_->find(id) != nullptr && impl_->filters[id.index].sensor;
}

const std::vector<SensorEvent>& World::sensor_events() const {
  return impl_->sensor_tracker.events();
}
std::size_t World::sensor_overlaps() const { return impl_->sensor_tracker.overlap_count(); }

std::size_t World::body_count() const { return impl_->alive_count(); }

std::size_t World::dynamic_body_count() const { return impl_->dynamic_count(); }

std::size_t World::awake_body_count() const {
  return static_cast<std::size_t>(
      std::count_if(impl_->bodies.begin(), impl_->bodies.end(),
                    [](const Body& b) { return b.alive && b.is_dynamic() && b.awake; }));
}

void World::step(double dt) {
  assert(std::isfinite(dt) && dt > 0.0);
  impl_->query_index.forget_moving();
  impl_->step(dt);
}

std::uint64_t World::state_hash() const { return impl_->state_hash(); }
GameState& World::game_state() { return impl_->game_state; }
const GameState& World::game_state() const { return impl_->game_state; }
std::uint64_t World::step_count() const { return impl_->steps; }
void World::set_contact_events(bool on) {
  if (on == impl_->contact_events_on) return;
  impl_->contact_events_on = on;
  impl_->contact_tracker.clear();
}
bool World::contact_events_on() const { return impl_->contact_events_on; }
const std::vector<ContactEvent>& World::contact_events() const {
  return impl_->contact_tracker.events();
}
std::size_t World::contacts_in_touch() const { return impl_->contact_tracker.contact_count(); }
const WorldSettings& World::settings() const { return impl_->settings; }
const StageCounters& World::counters() const { return impl_->counters; }
const StepProfile& World::last_profile() const { return impl_->profile; }

}  // namespace phys
