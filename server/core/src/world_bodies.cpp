// WorldImpl's bodies and their slots: a body definition checked and added,
// removed, found by id and by name, woken, filtered, read out as a BodyState, and
// the state hash over all of them.
#include <algorithm>
#include <cassert>
#include <cmath>

#include "physics/fnv_hash.h"
#include "physics/formulas.h"
#include "world_impl.h"
#include "world_limits.h"

namespace phys {

WorldImpl::WorldImpl(const WorldSettings& s) : settings(s) {
  assert(check_settings(s) == SettingsError::None);
}

BodyDefError WorldImpl::check(const BodyDef& def) const {
  if (!is_finite(def.position)) return BodyDefError::NonFinitePosition;
  if (!within_coordinate_limit(def.position)) return BodyDefError::OutOfBounds;
  if (!is_finite(def.velocity)) return BodyDefError::NonFiniteVelocity;
  if (!is_finite(def.acceleration)) return BodyDefError::NonFiniteAcceleration;
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (def.shape == Shape::Circle) {
    if (!positive(def.radius)) return BodyDefError::BadRadius;
    if (def.radius > settings.max_body_size) return BodyDefError::TooLarge;
  } else {
    if (!positive(def.half_extents.x) || !positive(def.half_extents.y)) {
      return BodyDefError::BadHalfExtents;
    }
    if (std::max(def.half_extents.x, def.half_extents.y) > settings.max_body_size) {
      return BodyDefError::TooLarge;
    }
  }
  if (def.motion == Motion::Dynamic && !positive(def.mass)) return BodyDefError::BadMass;
  if (def.motion == Motion::Kinematic && def.acceleration != Vec2{}) {
    return BodyDefError::KinematicAcceleration;
  }
  if (!std::isfinite(def.restitution) || def.restitution < 0.0 || def.restitution > 1.0) {
    return BodyDefError::BadRestitution;
  }
  if (!is_finite(def.friction) || def.friction.x < 0.0 || def.friction.y < 0.0 ||
      !std::isfinite(def.contact_friction) || def.contact_friction < 0.0) {
    return BodyDefError::BadFriction;
  }
  if (settings.has_bounds && !contains(settings.bounds, def.position)) {
    return BodyDefError::OutOfBounds;
  }
  if (def.name.size() > kMaxBodyNameBytes) return BodyDefError::BadName;
  if (alive_count_ >= settings.max_bodies) return BodyDefError::TooManyBodies;
  return BodyDefError::None;
}

BodyId WorldImpl::add_body(const BodyDef& def, BodyDefError* error) {
  const BodyDefError problem = check(def);
  if (error) *error = problem;
  if (problem != BodyDefError::None) return BodyId::invalid();

  std::uint32_t index;
  if (!free_slots_.empty()) {
    index = free_slots_.back();
    free_slots_.pop_back();
  } else {
    index = static_cast<std::uint32_t>(bodies.size());
    bodies.emplace_back();
    warm.emplace_back();
    warm_count.push_back(0);
    warm_first.push_back(kWarmInSlot);
    filters.emplace_back();
    names.emplace_back();
  }
  Body& b = bodies[index];
  warm_count[index] = 0;
  warm_first[index] = kWarmInSlot;
  const std::uint32_t generation = b.generation + 1;
  b = Body{};
  b.generation = generation;
  b.alive = true;
  b.shape = def.shape;
  b.motion = def.motion;
  b.position = def.position;
  b.radius = def.shape == Shape::Circle ? def.radius : 0.0;
  b.half = half_size(def.shape, def.radius, def.half_extents);
  b.restitution = def.restitution;
  b.friction = def.friction;
  b.contact_friction = def.contact_friction;
  if (def.motion == Motion::Dynamic) {
    // A definition is held to the same limits as the setters: the world stays finite.
    b.velocity = clamp_counted(def.velocity, settings.max_speed, counters.speed_clamps);
    b.acceleration =
        clamp_counted(def.acceleration, settings.max_acceleration, counters.acceleration_clamps);
    b.mass = def.mass;
    b.inv_mass = 1.0 / def.mass;
    ++dynamic_count_;
  } else if (def.motion == Motion::Kinematic) {
    b.velocity = clamp_counted(def.velocity, settings.max_speed, counters.speed_clamps);
    ++kinematic_count_;
  }
  filters[index] = {def.filter, def.is_sensor};
  if (!filters[index].is_default()) ++filtered_count_;
  if (def.is_sensor) sensors.insert(std::upper_bound(sensors.begin(), sensors.end(), index), index);
  names[index] = def.name;
  if (!def.name.empty()) {
    const std::pair<std::string, std::uint32_t> entry{def.name, index};
    name_index.insert(std::upper_bound(name_index.begin(), name_index.end(), entry), entry);
  }
  ++alive_count_;
  lists_dirty_ = true;
  rebuild_all_ = true;
  if (def.motion == Motion::Static) {
    query_index.forget_static();
  } else {
    query_index.forget_moving();
  }
  return {index, generation};
}

Body* WorldImpl::find(BodyId id) {
  if (id.index >= bodies.size()) return nullptr;
  Body& b = bodies[id.index];
  return (b.alive && b.generation == id.generation) ? &b : nullptr;
}

const Body* WorldImpl::find(BodyId id) const { return const_cast<WorldImpl*>(this)->find(id); }

bool WorldImpl::remove_body(BodyId id) {
  Body* b = find(id);
  if (!b) return false;
  // Whatever rested on it must notice it is gone.
  const Aabb around{b->position - b->half - Vec2{settings.slop, settings.slop} * 2.0,
                    b->position + b->half + Vec2{settings.slop, settings.slop} * 2.0};
  wake_in(around, id.index);
  if (b->is_dynamic()) --dynamic_count_;
  if (b->motion == Motion::Kinematic) --kinematic_count_;
  BodyFilter& filter = filters[id.index];
  if (!filter.is_default()) --filtered_count_;
  if (filter.sensor) {
    sensors.erase(std::lower_bound(sensors.begin(), sensors.end(), id.index));
  }
  filter = {};
  if (!names[id.index].empty()) {
    const std::pair<std::string, std::uint32_t> entry{names[id.index], id.index};
    name_index.erase(std::lower_bound(name_index.begin(), name_index.end(), entry));
    names[id.index].clear();
  }
  --alive_count_;
  if (contact_events_on) contact_tracker.removed(id.index);
  if (b->motion == Motion::Static) {
    query_index.forget_static();
  } else if (b->is_dynamic() && !b->awake) {
    query_index.forget_sleeping();
  } else {
    query_index.forget_moving();
  }
  b->alive = false;
  free_slots_.push_back(id.index);
  lists_dirty_ = true;
  rebuild_all_ = true;
  return true;
}

void WorldImpl::wake_in(const Aabb& around, std::uint32_t except) {
  for (std::uint32_t i = 0; i < bodies.size(); ++i) {
    Body& o = bodies[i];
    if (o.alive && o.is_dynamic() && !o.awake && i != except) {
      if (boxes_intersect(o.bounds(), around)) wake(i);
    }
  }
}

void WorldImpl::set_filter(std::uint32_t slot, const Filter& filter) {
  BodyFilter& f = filters[slot];
  if (f.filter == filter) return;
  if (!f.is_default()) --filtered_count_;
  f.filter = filter;
  if (!f.is_default()) ++filtered_count_;
  // Pairs it may meet now, or no longer: found anew, with whatever rests on it or
  // under it awake to notice.
  const Body& b = bodies[slot];
  const Vec2 margin{2.0 * settings.slop, 2.0 * settings.slop};
  wake_in({b.position - b.half - margin, b.position + b.half + margin}, kNoSlot);
  wake(slot);
  candidates.valid = false;
}

std::uint32_t WorldImpl::find_name(std::string_view name) const {
  const auto it = std::lower_bound(name_index.begin(), name_index.end(), name,
                                   [](const std::pair<std::string, std::uint32_t>& e,
                                      std::string_view n) { return e.first < n; });
  return it != name_index.end() && it->first == name ? it->second : kNoSlot;
}

void WorldImpl::wake(std::uint32_t index) {
  Body& b = bodies[index];
  b.still_time = 0.0;
  b.still_anchor = b.position;
  if (b.alive && b.is_dynamic() && !b.awake) {
    b.awake = true;
    ++counters.wakes;
    lists_dirty_ = true;
    query_index.forget_sleeping();
    query_index.forget_moving();
    changed_slots_.push_back(index);
  }
}

BodyState WorldImpl::state_of(std::uint32_t index) const {
  const Body& b = bodies[index];
  BodyState s;
  s.id = {index, b.generation};
  s.shape = b.shape;
  s.motion = b.motion;
  s.position = b.position;
  s.velocity = b.velocity;
  s.acceleration = b.acceleration;
  s.radius = b.radius;
  s.half_extents = b.shape == Shape::Box ? b.half : Vec2{};
  s.mass = b.mass;
  s.restitution = b.restitution;
  s.friction = b.friction;
  s.contact_friction = b.contact_friction;
  s.awake = b.is_dynamic() && b.awake;
  return s;
}

// FNV-1a over 64-bit words of the exact bit patterns, in slot order.
std::uint64_t WorldImpl::state_hash() const {
  Fnv1a64 h;
  for (std::uint32_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    if (!b.alive) continue;
    h.mix((static_cast<std::uint64_t>(b.generation) << 32) | i);
    h.mix(static_cast<std::uint64_t>(b.shape) | (static_cast<std::uint64_t>(b.motion) << 8));
    h.mix_double(b.position.x);
    h.mix_double(b.position.y);
    h.mix_double(b.velocity.x);
    h.mix_double(b.velocity.y);
    h.mix_double(b.acceleration.x);
    h.mix_double(b.acceleration.y);
    h.mix_double(b.half.x);
    h.mix_double(b.half.y);
    // Filters and sensors only where they are not the default, so that a world
    // without them hashes as it did before they existed. (A kinematic body's motion
    // is in the word above; names are labels, not state of the physics.)
    if (filtered_count_ != 0 && !filters[i].is_default()) {
      const BodyFilter& f = filters[i];
      h.mix(f.filter.category_bits | (static_cast<std::uint64_t>(f.filter.mask_bits) << 32));
      h.mix(static_cast<std::uint32_t>(f.filter.group) |
            (static_cast<std::uint64_t>(f.sensor ? 1 : 0) << 32));
    }
  }
  // The game state only when there is some, so that a world without it hashes as it
  // did before worlds held one.
  if (!game_state.empty()) {
    h.mix(0x67616d6573746174ull);  // "gamestat": the game state starts here
    game_state.mix_into(h);
  }
  return h.value();
}

std::size_t WorldImpl::state_bytes() const {
  const auto held = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return sizeof(WorldImpl) + held(bodies) + held(warm_count) + held(warm_first) + held(warm) +
         held(warm_pool) + held(lists.active) + held(lists.fixed) + held(lists.fixed_boxes) +
         held(candidates.list) + held(candidates.first) + held(candidates.fat_boxes) +
         held(free_slots_) + held(changed_slots_) + contact_tracker.state_bytes() +
         lists.fixed_grid.state_bytes() + game_state.heap_bytes();
}

}  // namespace phys
