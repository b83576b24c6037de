#include "contact_tracker.h"

#include <algorithm>

#include "world_impl.h"

namespace phys {

void ContactTracker::clear() {
  touches_.clear();
  order_.clear();
  current_.clear();
  next_.clear();
  events_.clear();
  stepped_.clear();
  serial_ = 0;
  removed_flag_.clear();
  removed_.clear();
}

void ContactTracker::begin_step() {
  touches_.clear();
  events_.clear();
  ++serial_;
}

void ContactTracker::mark_stepped(const std::vector<std::uint32_t>& slots, std::size_t slot_count) {
  if (stepped_.size() < slot_count) stepped_.resize(slot_count, 0);
  for (const std::uint32_t slot : slots) stepped_[slot] = serial_;
}

void ContactTracker::note(BodyId a, BodyId b, Vec2 point, Vec2 normal, double closing) {
  if (a.index > b.index) {
    std::swap(a, b);
    normal = Vec2{} - normal;  // not -normal: a zero component stays +0 (printed "0", not "-0")
  }
  const Pair pair{(std::uint64_t{a.index} << 32) | b.index, a.generation, b.generation};
  touches_.push_back({pair, static_cast<std::uint32_t>(touches_.size()), point, normal, closing});
}

void ContactTracker::removed(std::uint32_t slot) {
  if (removed_flag_.size() <= slot) removed_flag_.resize(slot + 1, 0);
  if (removed_flag_[slot] == 0) removed_.push_back(slot);
  removed_flag_[slot] = 1;
}

bool ContactTracker::removals_consistent(std::size_t slots) const {
  if (removed_flag_.size() > slots) return false;
  std::vector<std::uint8_t> unlisted(removed_flag_);
  for (const std::uint32_t slot : removed_) {
    if (slot >= unlisted.size() || unlisted[slot] != 1) return false;
    unlisted[slot] = 0;
  }
  return std::all_of(unlisted.begin(), unlisted.end(), [](std::uint8_t f) { return f == 0; });
}

std::size_t ContactTracker::finish(std::uint64_t step, const std::vector<Body>& bodies) {
  // The first touch of each pair (a pair may be noted by a swept hit and by the
  // overlap test, and once per sub-step), in pair order: a step's touches name each
  // slot with its one generation, so the slots alone order them. Sorted as 16-byte
  // keys, not as the touches themselves.
  order_.resize(touches_.size());
  for (std::size_t i = 0; i < touches_.size(); ++i) {
    order_[i] = {touches_[i].pair.slots, static_cast<std::uint32_t>(i)};
  }
  std::sort(order_.begin(), order_.end(), [](const Keyed& x, const Keyed& y) {
    return x.slots < y.slots || (x.slots == y.slots && x.index < y.index);
  });
  order_.erase(std::unique(order_.begin(), order_.end(),
                           [](const Keyed& x, const Keyed& y) { return x.slots == y.slots; }),
               order_.end());

  // A body's velocity now, for an end (a removed body counts as still).
  const auto velocity_of = [&](BodyId id) {
    if (was_removed(id.index) || id.index >= bodies.size()) return Vec2{};
    const Body& b = bodies[id.index];
    return b.alive && b.generation == id.generation && b.is_dynamic() && b.awake ? b.velocity
                                                                                 : Vec2{};
  };

  next_.clear();
  std::size_t i = 0;  // into current_
  std::size_t j = 0;  // into order_
  while (i < current_.size() || j < order_.size()) {
    const bool have_touch = j < order_.size();
    const bool have_old = i < current_.size();
    static const Touch kNone{};
    const Touch& t = have_touch ? touches_[order_[j].index] : kNone;
    if (have_old && have_touch && current_[i].pair == t.pair) {  // still in contact
      next_.push_back({t.pair, t.point, t.normal});
      ++i;
      ++j;
    } else if (have_old && (!have_touch || current_[i].pair < t.pair)) {  // not seen this step
      const Contacting& c = current_[i++];
      const std::uint32_t a = c.pair.a().index;
      const std::uint32_t b = c.pair.b().index;
      if (!was_removed(a) && !was_removed(b) && !stepped(a) && !stepped(b)) {
        next_.push_back(c);  // neither moved: static or asleep
        continue;
      }
      const double closing = -dot(velocity_of(c.pair.b()) - velocity_of(c.pair.a()), c.normal);
      events_.push_back(
          {ContactEventKind::End, step, c.pair.a(), c.pair.b(), c.point, c.normal, closing});
    } else {  // seen for the first time
      next_.push_back({t.pair, t.point, t.normal});
      events_.push_back(
          {ContactEventKind::Begin, step, t.pair.a(), t.pair.b(), t.point, t.normal, t.closing});
      ++j;
    }
  }
  std::swap(current_, next_);
  for (const std::uint32_t slot : removed_) removed_flag_[slot] = 0;
  removed_.clear();
  return events_.size();
}

}  // namespace phys
