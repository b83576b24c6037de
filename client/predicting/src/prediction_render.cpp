// What the prediction shows: the moving bodies with the corrections a rollback left
// still decaying (Overwatch, Rocket League: the eye sees a glide, not a snap).
#include <algorithm>

#include "client/prediction_core.h"

namespace client {
namespace {

phys::BodyId id_of(std::uint64_t packed) { return phys::BodyId::from_packed(packed); }

// Below this a correction is gone (m): a nanometre is far under a pixel.
constexpr double kNegligibleCorrection = 1e-9;

}  // namespace

std::vector<PredictionCore::Position> PredictionCore::positions() const {
  std::vector<Position> out;
  out.reserve(world_.dynamic_body_count());
  world_.for_each_body([&](const phys::BodyState& body) {
    if (body.motion != phys::Motion::Static) out.push_back({body.id.packed(), body.position});
  });
  return out;
}

void PredictionCore::add_corrections(const std::vector<Position>& before) {
  for (const Position& old : before) {
    const auto now = world_.body(id_of(old.id));
    if (!now) continue;
    const phys::Vec2 delta = old.position - now->position;
    const double size = phys::length(delta);
    if (size == 0.0) continue;
    stats_.largest_correction = std::max(stats_.largest_correction, size);
    phys::Vec2& shown = corrections_[old.id];
    shown += delta;
    const double total = phys::length(shown);
    if (total > config_.snap_distance) {
      // Too far to glide: shown where it is at once.
      stats_.largest_smoothed_correction = std::max(stats_.largest_smoothed_correction, total);
      corrections_.erase(old.id);
    }
  }
}

void PredictionCore::decay_corrections(std::uint64_t ticks) {
  for (auto it = corrections_.begin(); it != corrections_.end();) {
    if (!world_.contains(id_of(it->first))) {
      it = corrections_.erase(it);
      continue;
    }
    // Past a few hundred ticks any correction is long gone.
    for (std::uint64_t i = 0; i < std::min<std::uint64_t>(ticks, 1000); ++i) {
      const double moved = phys::length(it->second) * (1.0 - decay_per_tick_);
      stats_.largest_smoothed_correction = std::max(stats_.largest_smoothed_correction, moved);
      it->second = it->second * decay_per_tick_;
    }
    if (phys::length(it->second) < kNegligibleCorrection) {
      it = corrections_.erase(it);
    } else {
      ++it;
    }
  }
}

Vec2 PredictionCore::correction(std::uint64_t body_id) const {
  const auto it = corrections_.find(body_id);
  if (it == corrections_.end()) return {};
  return {it->second.x, it->second.y};
}

RenderState PredictionCore::render() const {
  RenderState state;
  state.tick = world_tick_;
  state.bodies.reserve(world_.dynamic_body_count());
  world_.for_each_body([&](const phys::BodyState& body) {
    if (body.motion == phys::Motion::Static) return;
    RenderBody& shown = state.bodies.emplace_back();
    shown.body_id = body.id.packed();
    shown.motion = body.motion == phys::Motion::Kinematic ? Motion::Kinematic : Motion::Dynamic;
    shown.predicted_position = {body.position.x, body.position.y};
    shown.velocity = {body.velocity.x, body.velocity.y};
    const Vec2 offset = correction(shown.body_id);
    shown.position = {body.position.x + offset.x, body.position.y + offset.y};
  });
  return state;
}

}  // namespace client
