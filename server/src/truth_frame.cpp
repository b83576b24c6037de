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
  std::size_t p = 0;
  world.for_each_body([&](const phys::BodyState& body) {
    if (body.motion != phys::Motion::Dynamic) return;
    TruthBody t;
    t.id = body.id.packed();
    t.x = body.position.x;
    t.y = body.position.y;
    t.vx = body.velocity.x;
    t.vy = body.velocity.y;
    t.awake = body.awake;
    t.previous_x = t.x;
    t.previous_y = t.y;
    t.previous_vx = t.vx;
    t.previous_vy = t.vy;
    if (previous != nullptr) {
      const auto& before = previous->bodies;
      while (p < before.size() && before[p].id < t.id) ++p;
      if (p < before.size() && before[p].id == t.id) {
        t.previous_x = before[p].x;
        t.previous_y = before[p].y;
        t.previous_vx = before[p].vx;
        t.previous_vy = before[p].vy;
      }
    }
    frame.bodies.push_back(t);
  });
  return frame;
}

}  // namespace server
