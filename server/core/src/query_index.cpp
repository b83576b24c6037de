// Filing the bodies for queries, and walking a cast's path through the grids.
#include "query_index.h"

#include <algorithm>
#include <cmath>

#include "world_impl.h"

namespace phys {

namespace {

// Candidate boxes are grown by this much of the coordinates' magnitude: a thousand
// times wider than the rounding of a point along a cast or of a circle's box, so the
// grids, which only choose whom to test, never leave out a body the exact tests find.
constexpr double kMarginPerUnit = 1.0e-9;
// At most this many chunks along a cast's path through a grid (a grid of N boxes has
// about sqrt(2 N) cells a side, so only a path across a grid of millions reaches it;
// the chunks are then longer, never wrong).
constexpr double kMaxChunks = 4096.0;

double margin_for(std::initializer_list<double> values) {
  double largest = 0.0;
  for (double v : values) largest = std::max(largest, std::fabs(v));
  return kMarginPerUnit * (1.0 + largest);
}

Aabb grown(const Aabb& box, double by) { return {box.min - Vec2{by, by}, box.max + Vec2{by, by}}; }

// The part of [0, 1] along which a box of half size `reach`, moved from origin along
// translation, can meet `bounds`. False if nowhere.
bool clip_to(const Aabb& bounds, Vec2 origin, Vec2 translation, Vec2 reach, double& t0,
             double& t1) {
  t0 = 0.0;
  t1 = 1.0;
  const double lo[2] = {bounds.min.x - reach.x, bounds.min.y - reach.y};
  const double hi[2] = {bounds.max.x + reach.x, bounds.max.y + reach.y};
  const double from[2] = {origin.x, origin.y};
  const double delta[2] = {translation.x, translation.y};
  for (int axis = 0; axis < 2; ++axis) {
    if (delta[axis] == 0.0) {
      if (from[axis] < lo[axis] || from[axis] > hi[axis]) return false;
      continue;
    }
    double near = (lo[axis] - from[axis]) / delta[axis];
    double far = (hi[axis] - from[axis]) / delta[axis];
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
  }
  return t0 <= t1;
}

}  // namespace

void QueryIndex::Part::file(std::span<const Body> bodies) {
  boxes.clear();
  bounds = {{HUGE_VAL, HUGE_VAL}, {-HUGE_VAL, -HUGE_VAL}};
  for (const std::uint32_t slot : slots) {
    const Aabb box = bodies[slot].bounds();
    boxes.push_back(box);
    bounds = {{std::min(bounds.min.x, box.min.x), std::min(bounds.min.y, box.min.y)},
              {std::max(bounds.max.x, box.max.x), std::max(bounds.max.y, box.max.y)}};
  }
  grid.build(boxes);
  valid = true;
}

void QueryIndex::refresh(std::span<const Body> bodies, const BodyLists* lists) {
  if (static_.valid && sleeping_.valid && moving_.valid) return;
  const auto is_static = [](const Body& b) { return b.motion == Motion::Static; };
  const auto is_sleeping = [](const Body& b) { return b.is_dynamic() && !b.awake; };
  const auto collect = [&bodies](Part& part, const auto& belongs) {
    part.slots.clear();
    for (std::uint32_t slot = 0; slot < bodies.size(); ++slot) {
      if (bodies[slot].alive && belongs(bodies[slot])) part.slots.push_back(slot);
    }
    part.file(bodies);
  };
  if (!static_.valid) collect(static_, is_static);
  if (!sleeping_.valid) collect(sleeping_, is_sleeping);
  if (moving_.valid) return;
  if (lists != nullptr) {
    moving_.slots.assign(lists->active.begin(), lists->active.end());
    for (const std::uint32_t f : lists->kinematic) moving_.slots.push_back(lists->fixed[f]);
    moving_.file(bodies);
  } else {
    collect(moving_, [&](const Body& b) { return !is_static(b) && !is_sleeping(b); });
  }
}

void QueryIndex::overlapping(const Aabb& box, std::vector<std::uint32_t>& out) const {
  out.clear();
  const Aabb query = grown(box, margin_for({box.min.x, box.min.y, box.max.x, box.max.y}));
  for (const Part* part : {&static_, &sleeping_, &moving_}) {
    if (part->slots.empty()) continue;
    part->grid.find_overlaps(query, found_);
    for (std::uint32_t i : found_) out.push_back(part->slots[i]);
  }
  std::sort(out.begin(), out.end());
}

void QueryIndex::sweep(Vec2 origin, Vec2 translation, Vec2 reach, const ChunkVisit& visit) const {
  const double margin =
      margin_for({origin.x, origin.y, translation.x, translation.y, reach.x, reach.y});
  double best = HUGE_VAL;
  for (const Part* part : {&static_, &sleeping_, &moving_}) {
    sweep_part(*part, origin, translation, reach, margin, best, visit);
  }
}

void QueryIndex::sweep_part(const Part& part, Vec2 origin, Vec2 translation, Vec2 reach,
                            double margin, double& best, const ChunkVisit& visit) const {
  if (part.slots.empty()) return;
  double t0 = 0.0;
  double t1 = 1.0;
  if (!clip_to(grown(part.bounds, margin), origin, translation, reach, t0, t1)) return;
  // Chunks about a cell long, so each asks the grid for a few cells.
  const double path = (t1 - t0) * length(translation);
  const double chunks = std::clamp(std::ceil(path / part.grid.cell_size()), 1.0, kMaxChunks);
  const auto count = static_cast<int>(chunks);
  const Vec2 pad = reach + Vec2{margin, margin};
  for (int k = 0; k < count; ++k) {
    const double ta = t0 + (t1 - t0) * (static_cast<double>(k) / chunks);
    const double tb = k + 1 == count ? t1 : t0 + (t1 - t0) * (static_cast<double>(k + 1) / chunks);
    const Vec2 a = origin + translation * ta;
    const Vec2 b = origin + translation * tb;
    const Aabb chunk{Vec2{std::min(a.x, b.x), std::min(a.y, b.y)} - pad,
                     Vec2{std::max(a.x, b.x), std::max(a.y, b.y)} + pad};
    part.grid.find_overlaps(chunk, found_);
    if (!found_.empty()) {
      chunk_.clear();
      for (std::uint32_t i : found_) chunk_.push_back(part.slots[i]);
      best = std::min(best, visit(chunk_));
    }
    if (best < tb) return;
  }
}

}  // namespace phys
