// What World::from_bytes checks of a state it read, before it trusts it: every
// index in range, every count as the arrays say, every value the world itself
// would have refused refused here (world_bytes.cpp reads the bytes).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "world_impl.h"

namespace phys {

namespace {

// A finite value past one of the world's own limits (a speed over max_speed, a
// size over max_body_size) is one the world would have clamped or refused, and the
// step's arithmetic may overflow on it: refused too. The limits allow a rounding
// over, as clamp_length leaves a length a rounding over its limit.
bool within(double value, double limit) { return std::fabs(value) <= limit * (1.0 + 1.0e-9); }

std::string check_body_limits(const Body& b, const WorldSettings& s) {
  if (!within(b.velocity.x, s.max_speed) || !within(b.velocity.y, s.max_speed)) {
    return "moves faster than the world's max_speed";
  }
  if (!within(b.acceleration.x, s.max_acceleration) ||
      !within(b.acceleration.y, s.max_acceleration)) {
    return "has an acceleration over the world's max_acceleration";
  }
  if (!(b.radius >= 0.0) || !within(b.radius, s.max_body_size) || !(b.half.x > 0.0) ||
      !(b.half.y > 0.0) || !within(b.half.x, s.max_body_size) ||
      !within(b.half.y, s.max_body_size)) {
    return "has a size out of the world's range";
  }
  // The material and the step's carried-over values, as add_body checks the first.
  const double carried[] = {b.correction.x, b.correction.y,   b.load,          b.held.x,
                            b.held.y,       b.still_anchor.x, b.still_anchor.y};
  for (const double v : carried) {
    if (!std::isfinite(v)) return "holds a non-finite number";
  }
  // What the contacts held of a resting body's acceleration is at most that
  // acceleration (its own, clamped, plus gravity) on each axis.
  if (!within(b.held.x, s.max_acceleration + std::fabs(s.gravity.x)) ||
      !within(b.held.y, s.max_acceleration + std::fabs(s.gravity.y))) {
    return "holds more support than its acceleration";
  }
  if (!(b.restitution >= 0.0 && b.restitution <= 1.0)) return "has a restitution outside [0, 1]";
  if (!(b.contact_friction >= 0.0) || !std::isfinite(b.contact_friction) ||
      !(b.friction.x >= 0.0) || !std::isfinite(b.friction.x) || !(b.friction.y >= 0.0) ||
      !std::isfinite(b.friction.y)) {
    return "has a friction that is negative or not finite";
  }
  if (b.is_dynamic() && (!(b.mass > 0.0) || b.inv_mass != 1.0 / b.mass)) {
    return "is dynamic with a mass that is not positive or an inverse mass that is not its inverse";
  }
  return {};
}

// The bodies: known shapes and motions, finite numbers within the world's limits,
// warm-start entries where they can be, and the counts as the bodies say.
std::string check_bodies(const WorldImpl& w) {
  const std::size_t slots = w.bodies.size();
  if (w.warm_count.size() != slots || w.warm_first.size() != slots) {
    return "its warm-start arrays do not have one entry per body slot";
  }
  std::size_t alive = 0;
  std::size_t dynamic = 0;
  for (std::size_t i = 0; i < slots; ++i) {
    const Body& b = w.bodies[i];
    if (b.shape != Shape::Circle && b.shape != Shape::Box) return "a body has an unknown shape";
    if (b.motion != Motion::Static && b.motion != Motion::Dynamic &&
        b.motion != Motion::Kinematic) {
      return "a body has an unknown motion";
    }
    const double numbers[] = {b.position.x,     b.position.y,     b.half.x, b.half.y,
                              b.velocity.x,     b.velocity.y,     b.radius, b.inv_mass,
                              b.acceleration.x, b.acceleration.y, b.mass,   b.still_time};
    for (const double v : numbers) {
      if (!std::isfinite(v)) return "body slot " + std::to_string(i) + " holds a non-finite number";
    }
    if (b.alive) {
      if (std::string problem = check_body_limits(b, w.settings); !problem.empty()) {
        return "body slot " + std::to_string(i) + " " + problem;
      }
    }
    if (w.warm_count[i] > kWarmSlots) return "a body has more warm-start entries than slots";
    if (w.warm_first[i] != kWarmInSlot &&
        (w.warm_first[i] > w.warm_pool.size() ||
         w.warm_pool.size() - w.warm_first[i] < w.warm_count[i])) {
      return "a body's warm-start entries lie outside the pool";
    }
    if (b.alive) {
      ++alive;
      if (b.is_dynamic()) ++dynamic;
    }
  }
  if (alive != w.alive_count() || dynamic != w.dynamic_count()) {
    return "its body counts do not match its bodies";
  }
  return {};
}

// Every slot a list, a name, a sensor or a tracker names exists, and the arrays
// kept per slot have one entry per slot.
std::string check_references(const WorldImpl& w, const std::vector<std::uint32_t>& changed_slots,
                             const std::vector<std::uint32_t>& free_slots) {
  const std::size_t slots = w.bodies.size();
  const auto in_slots = [&](const std::vector<std::uint32_t>& v) {
    for (const std::uint32_t s : v) {
      if (s >= slots) return false;
    }
    return true;
  };
  if (!in_slots(w.lists.active) || !in_slots(w.lists.fixed) || !in_slots(changed_slots)) {
    return "a body list names a slot that does not exist";
  }
  // Only the awake list's bodies keep their warm-start entries in the pool: the step
  // rewrites the pool and their places in it, and a body that leaves the list takes
  // its entries into its own slot (rebuild_lists). Any other body pointing into the
  // pool would be left pointing into a pool rewritten without it.
  {
    std::vector<std::uint8_t> awake(slots, 0);
    for (const std::uint32_t s : w.lists.active) awake[s] = 1;
    for (std::size_t i = 0; i < slots; ++i) {
      if (w.warm_first[i] != kWarmInSlot && !awake[i]) {
        return "a body not on the awake list keeps warm-start entries in the pool";
      }
    }
  }
  for (const std::uint32_t s : free_slots) {
    if (s >= slots || w.bodies[s].alive) return "a free slot is out of range or holds a body";
  }
  if (w.lists.joined > w.lists.active.size()) return "more joined bodies than awake ones";
  if (w.filters.size() != slots || w.names.size() != slots) {
    return "its filters or names do not have one entry per body slot";
  }
  for (const auto& [name, slot] : w.name_index) {
    if (slot >= slots) return "a name names a slot that does not exist";
  }
  if (!in_slots(w.sensors)) return "a sensor names a slot that does not exist";
  for (const std::uint32_t k : w.lists.kinematic) {
    if (k >= w.lists.fixed.size()) return "a kinematic body's place is outside the static list";
  }
  if (!w.sensor_tracker.slots_below(slots))
    return "a sensor's overlap names a slot that does not exist";
  if (!w.contact_tracker.removals_consistent(slots)) {
    return "its contact events' removed bodies are not listed as a removal lists them";
  }
  return {};
}

// The awake and static lists hold each living body once, where its motion puts it;
// changed_slots (null when no body fell asleep or woke since the last rebuild): the
// bodies that may be elsewhere.
std::string check_list_membership(const WorldImpl& w,
                                  const std::vector<std::uint32_t>* changed_slots) {
  const std::size_t slots = w.bodies.size();
  // The lists as the last rebuild left them hold each living body once, where its
  // motion puts it, the static and sleeping ones by ascending slot. Until the next
  // rebuild only the bodies that fell asleep or woke since (changed_slots) may be
  // elsewhere: unless a whole rebuild is due, the next one moves only them.
  std::vector<std::uint8_t> changed(slots, 0);
  if (changed_slots != nullptr) {
    for (const std::uint32_t s : *changed_slots) changed[s] = 1;
  }
  std::vector<std::uint8_t> listed(slots, 0);
  for (const std::uint32_t s : w.lists.active) {
    const Body& b = w.bodies[s];
    if (listed[s]++ || (!changed[s] && (!b.alive || !b.is_dynamic() || !b.awake))) {
      return "the awake list holds a body that is not awake, or one twice";
    }
  }
  for (std::size_t f = 0; f < w.lists.fixed.size(); ++f) {
    const std::uint32_t s = w.lists.fixed[f];
    const Body& b = w.bodies[s];
    if (listed[s]++ || (f > 0 && s < w.lists.fixed[f - 1]) ||
        (!changed[s] && (!b.alive || (b.is_dynamic() && b.awake)))) {
      return "the static list holds a body that moves, or one twice, or is out of order";
    }
  }
  return {};
}

// The static boxes and the candidate pairs match the lists they were made from.
std::string check_candidates(const WorldImpl& w) {
  const std::size_t slots = w.bodies.size();
  if (w.lists.fixed_boxes.size() != w.lists.fixed.size()) {
    return "the static and sleeping bodies' boxes do not match their list";
  }
  if (w.candidates.valid) {
    const std::size_t positions = w.lists.active.size();
    if (w.candidates.first.size() != positions + 1 || w.candidates.fat_boxes.size() != positions ||
        w.candidates.first.back() != w.candidates.list.size()) {
      return "the candidate pairs do not match the awake bodies";
    }
    for (std::size_t p = 0; p < positions; ++p) {
      if (w.candidates.first[p] > w.candidates.first[p + 1]) {
        return "the candidate pairs' offsets go backwards";
      }
    }
    for (const Candidate& c : w.candidates.list) {
      if (c.lower >= slots || c.upper >= slots || c.lower_pos >= positions ||
          (!c.fixed && c.upper_pos >= positions)) {
        return "a candidate pair names a body that does not exist";
      }
    }
  }
  return {};
}

}  // namespace

// What the reader cannot take on trust: every index in range, every count as the
// arrays say, every value the world itself would have refused refused here.
std::string check_read_state(const WorldImpl& w) {
  if (w.settings.integrator > Integrator::Exact) return "its settings name an unknown integrator";
  if (check_settings(w.settings) != SettingsError::None) return "its settings are not valid";
  if (std::string problem = check_bodies(w); !problem.empty()) return problem;
  if (std::string problem = check_references(w, w.changed_slots_, w.free_slots_);
      !problem.empty()) {
    return problem;
  }
  if (!w.lists_dirty_ || !w.rebuild_all_) {
    const std::vector<std::uint32_t>* changed = w.lists_dirty_ ? &w.changed_slots_ : nullptr;
    if (std::string problem = check_list_membership(w, changed); !problem.empty()) return problem;
  }
  return check_candidates(w);
}

}  // namespace phys
