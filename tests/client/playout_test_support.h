#pragma once
// The playout buffer tests' scene: three bodies with known trajectories (one moving
// in a line, one round a circle, one at rest) sampled at the server's tick rate.
#include <cmath>
#include <cstdint>

#include "client/playout_buffer.h"

namespace playout_test {

// The buffer's names, for the tests that use this namespace.
using client::PlayoutBuffer;
using client::PlayoutFrame;
using client::PlayoutSettings;
using client::PlayoutStatus;
using client::PushResult;

constexpr double kTickRate = 60.0;
constexpr double kLatency = 0.050;      // the fastest transit, s
constexpr double kFrame = 1.0 / 144.0;  // the display's frame time, s
constexpr std::uint64_t kLinear = 1;    // moves at a constant velocity
constexpr std::uint64_t kCircle = 2;    // goes round a circle
constexpr std::uint64_t kResting = 3;   // never moves
inline const client::Vec2 kVelocity{3.0, -1.0};
constexpr double kRadius = 1.0;
constexpr double kOmega = 2.0;  // rad/s: 2 m/s on the circle

inline client::Vec2 linear_at(double t) { return {1.0 + kVelocity.x * t, 2.0 + kVelocity.y * t}; }

inline client::Snapshot snapshot_at(std::uint64_t tick) {
  const double t = static_cast<double>(tick) / kTickRate;
  client::Snapshot s;
  s.tick = tick;
  s.bodies.push_back({kLinear, linear_at(t), kVelocity});
  s.bodies.push_back(
      {kCircle,
       {kRadius * std::cos(kOmega * t), kRadius * std::sin(kOmega * t)},
       {-kRadius * kOmega * std::sin(kOmega * t), kRadius * kOmega * std::cos(kOmega * t)}});
  s.bodies.push_back({kResting, {5.0, 0.5}, {0.0, 0.0}});
  return s;
}

inline const client::PlayoutBody* body(const client::PlayoutFrame& frame, std::uint64_t id) {
  for (const auto& b : frame.bodies)
    if (b.body_id == id) return &b;
  return nullptr;
}

inline double distance(const client::Vec2& a, const client::Vec2& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

}  // namespace playout_test
