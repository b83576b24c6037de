#include "truth_frame.h"

#include <algorithm>

namespace server {

const TruthBody* TruthFrame::find(std::uint64_t id) const {
  const auto it = std::lower_bound(bodies.begin(), bodies.end(), id,
                                   [](const TruthBody& b, std::uint64_t v) { return b.id < v; });
  return it != bodies.end() && it->id == id ? &*it : nullptr;
}

TruthFrame read_truth(const phys::World& world, std::uint64_t tick, const TruthFrame* previous) {
  TruthFrame frame;
  frame.tick = tick;
  frame.state_hash = world.state_hash();
  frame.bodies.reserve(world.dynamic_body_count());
  world.for_each_body([&](const phys::BodyState& body) {
    // A static body never moves by itself; a kinematic one does, every tick.
    if (body.motion == phys::Motion::Static) return;
    TruthBody t;
    t.id = body.id.packed();
    t.x = body.position.x;
    t.y = body.position.y;
    t.vx = body.velocity.x;
    t.vy = body.velocity.y;
    t.awake = body.awake;
    t.kinematic = body.motion == phys::Motion::Kinematic;
    frame.bodies.push_back(t);
  });
  // The world walks its slots in index order, and a packed id puts the slot's
  // generation above its index: once a freed slot is reused (a client left and
  // another joined), index order is no longer id order. Views write ids as
  // ascending gaps, so the frame is put in id order here (one check per tick; a
  // sort only after such a reuse).
  const auto by_id = [](const TruthBody& a, const TruthBody& b) { return a.id < b.id; };
  if (!std::is_sorted(frame.bodies.begin(), frame.bodies.end(), by_id)) {
    std::sort(frame.bodies.begin(), frame.bodies.end(), by_id);
  }
  std::size_t p = 0;
  for (TruthBody& t : frame.bodies) {
    t.previous_x = t.x;
    t.previous_y = t.y;
    t.previous_vx = t.vx;
    t.previous_vy = t.vy;
    if (previous == nullptr) continue;
    const auto& before = previous->bodies;
    while (p < before.size() && before[p].id < t.id) ++p;
    if (p < before.size() && before[p].id == t.id) {
      t.previous_x = before[p].x;
      t.previous_y = before[p].y;
      t.previous_vx = before[p].vx;
      t.previous_vy = before[p].vy;
    }
  }
  frame.contact_events = world.contact_events();
  for (phys::ContactEvent& event : frame.contact_events) event.step = tick;
  frame.sensor_events = world.sensor_events();
  for (phys::SensorEvent& event : frame.sensor_events) event.step = tick;
  return frame;
}

}  // namespace server
