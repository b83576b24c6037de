// Crush events (physics/crush_events.h): the step's crush pass (step_crush.cpp)
// records each pinned triple here, and World::crush_events hands out the last
// step's.
#include <algorithm>
#include <tuple>

#include "world_impl.h"

namespace phys {

namespace {

// Ids by slot, then generation: kinematic first, then dynamic, then static.
bool crush_before(const CrushEvent& a, const CrushEvent& b) {
  const auto key = [](const CrushEvent& e) {
    return std::tuple(e.kinematic.index, e.kinematic.generation, e.dynamic.index,
                      e.dynamic.generation, e.fixed.index, e.fixed.generation);
  };
  return key(a) < key(b);
}

}  // namespace

// Called within a step, before its count goes up: the step it is for is steps + 1.
// A triple pinned in several sub-steps is one event; the list stays sorted as it
// grows (a handful of crushes at most, in any game).
void WorldImpl::record_crush(std::uint32_t kinematic, std::uint32_t dynamic, std::uint32_t fixed) {
  const std::uint64_t step = steps + 1;
  if (!crushes.empty() && crushes.front().step != step) crushes.clear();
  const CrushEvent event{step,
                         {kinematic, bodies[kinematic].generation},
                         {dynamic, bodies[dynamic].generation},
                         {fixed, bodies[fixed].generation}};
  const auto at = std::lower_bound(crushes.begin(), crushes.end(), event, crush_before);
  if (at != crushes.end() && *at == event) return;
  crushes.insert(at, event);
}

const std::vector<CrushEvent>& World::crush_events() const {
  static const std::vector<CrushEvent> kNoCrushes;
  const std::vector<CrushEvent>& crushes = impl_->crushes;
  if (crushes.empty() || crushes.front().step != impl_->steps) return kNoCrushes;
  return crushes;
}

}  // namespace phys
