// The world's dense lists of bodies: the awake ones in processing order, and the
// static and sleeping ones (ascending slot) with their boxes and grid.
#include <algorithm>

#include "world_impl.h"

namespace phys {

namespace {
bool is_awake_dynamic(const Body& b) { return b.alive && b.is_dynamic() && b.awake; }
bool is_fixed(const Body& b) { return b.alive && !(b.is_dynamic() && b.awake); }
}  // namespace

void WorldImpl::rebuild_lists() {
  // The bodies that stay awake keep their places in the processing order: the step
  // keeps it sorted by height, nearly unchanged from one step to the next, and a
  // list rebuilt in slot order had to be sorted from scratch every step in which
  // any body of a settling pile fell asleep or woke. Their warm-start entries stay
  // in the pool too; only a body that leaves the list keeps its own in its slot.
  // (A slot reused by add_body since is already kWarmInSlot and empty.)
  previous_active_.swap(lists.active);
  lists.active.clear();
  listed_.resize(bodies.size(), 0);
  for (std::uint32_t slot : previous_active_) {
    if (is_awake_dynamic(bodies[slot])) {
      lists.active.push_back(slot);
      listed_[slot] = 1;
    } else if (warm_first[slot] != kWarmInSlot) {
      std::copy_n(warm_pool.begin() + warm_first[slot], warm_count[slot], warm[slot].entries);
      warm_first[slot] = kWarmInSlot;
    }
  }
  const std::size_t kept = lists.active.size();
  // A few bodies fell asleep or woke: only they are looked at. When many did (more
  // than an eighth of the bodies: a bound chosen, not measured), sorting them would
  // save little over the walk over every body.
  if (!rebuild_all_ && changed_slots_.size() <= bodies.size() / 8) {
    update_fixed_and_joined();
  } else {
    rebuild_fixed_and_joined();
  }
  for (std::size_t i = 0; i < kept; ++i) listed_[lists.active[i]] = 0;
  changed_slots_.clear();
  rebuild_all_ = false;
  lists.joined = kept == 0 ? 0 : lists.active.size() - kept;
  lists.kinematic.clear();
  if (kinematic_count_ != 0) {
    for (std::uint32_t f = 0; f < lists.fixed.size(); ++f) {
      if (bodies[lists.fixed[f]].motion == Motion::Kinematic) lists.kinematic.push_back(f);
    }
  }
  lists.fixed_grid.build(lists.fixed_boxes);
  lists_dirty_ = false;
  candidates.valid = false;
}

// Every body: the awake ones not kept join the awake list at its end (woken or
// added, in slot order), the rest are the static and sleeping ones.
void WorldImpl::rebuild_fixed_and_joined() {
  lists.fixed.clear();
  lists.fixed_boxes.clear();
  lists.fixed_circles = 0;
  lists.fixed_sleeping = 0;
  for (std::uint32_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    if (!b.alive) continue;
    if (is_awake_dynamic(b)) {
      if (!listed_[i]) lists.active.push_back(i);
    } else {
      lists.fixed.push_back(i);
      lists.fixed_boxes.push_back(b.bounds());
      lists.fixed_circles += b.shape == Shape::Circle ? 1 : 0;
      lists.fixed_sleeping += b.is_dynamic() ? 1 : 0;
    }
  }
}

// The same lists from the last ones and the bodies that fell asleep or woke since:
// every other body is where it was (asleep or static bodies do not move, and a body
// moved by hand asks for the whole rebuild), so the result is the whole rebuild's.
void WorldImpl::update_fixed_and_joined() {
  auto& changed = changed_slots_;
  // (A body that fell asleep and was woken by hand before this rebuild is there twice.)
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  for (std::uint32_t slot : changed) {
    if (is_awake_dynamic(bodies[slot]) && !listed_[slot]) lists.active.push_back(slot);
  }
  const auto count_in = [this](std::uint32_t slot) {
    lists.fixed_circles += bodies[slot].shape == Shape::Circle ? 1 : 0;
    lists.fixed_sleeping += bodies[slot].is_dynamic() ? 1 : 0;
  };
  const auto count_out = [this](std::uint32_t slot) {
    lists.fixed_circles -= bodies[slot].shape == Shape::Circle ? 1 : 0;
    lists.fixed_sleeping -= bodies[slot].is_dynamic() ? 1 : 0;
  };
  // Merged by slot: the fixed bodies that did not change, and the changed ones that
  // are fixed now.
  merged_fixed_.clear();
  merged_fixed_boxes_.clear();
  std::size_t i = 0;
  const auto keep_until = [&](std::uint32_t slot) {
    for (; i < lists.fixed.size() && lists.fixed[i] < slot; ++i) {
      merged_fixed_.push_back(lists.fixed[i]);
      merged_fixed_boxes_.push_back(lists.fixed_boxes[i]);
    }
  };
  for (std::uint32_t slot : changed) {
    keep_until(slot);
    if (i < lists.fixed.size() && lists.fixed[i] == slot) {  // it was fixed
      ++i;
      count_out(slot);
    }
    const Body& b = bodies[slot];
    if (is_fixed(b)) {
      merged_fixed_.push_back(slot);
      merged_fixed_boxes_.push_back(b.bounds());
      count_in(slot);
    }
  }
  keep_until(UINT32_MAX);
  lists.fixed.swap(merged_fixed_);
  lists.fixed_boxes.swap(merged_fixed_boxes_);
}

}  // namespace phys
