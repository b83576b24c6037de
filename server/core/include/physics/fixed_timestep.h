#pragma once
// The fixed-timestep driver of "Fix your timestep": elapsed wall time goes into an
// accumulator; while it holds a whole step, one update runs; at most max_steps run
// per frame and the rest of the backlog is dropped and counted (no spiral of
// death); what is left over is exposed as alpha for interpolation.
// Time is kept in integer nanoseconds so that N*period elapsed gives exactly N
// updates, with no rounding either way.
#include <chrono>
#include <cstdint>
#include <functional>

#include "physics/clock.h"

namespace phys {

// Ticks per second, wherever a rate comes from (a scene, physics-server's --tick-rate,
// a recording) and wherever it is stepped: in [kMinTickRate, kMaxTickRate]. The floor
// keeps dt = 1 / rate finite (a denormal rate would make it infinite); the ceiling is
// a 1 ms tick. scene/scene.h names the same two values for the scene's users.
inline constexpr double kMinTickRate = 0.001;
inline constexpr double kMaxTickRate = 1000.0;

struct FixedTimestepConfig {
  double tick_rate_hz = 60.0;
  int max_steps_per_frame = 6;
};

struct FrameResult {
  int steps = 0;                    // updates run this frame
  std::uint64_t dropped_steps = 0;  // whole steps of backlog thrown away this frame
};

class FixedTimestep {
 public:
  using Update = std::function<void(double dt)>;

  // tick_rate_hz in [kMinTickRate, kMaxTickRate], max_steps_per_frame >= 1.
  FixedTimestep(const Clock& clock, FixedTimestepConfig config);

  // Reads the clock once, adds the elapsed time, runs the updates due.
  FrameResult frame(const Update& update);

  // The seconds handed to each update: exactly 1 / tick_rate_hz.
  double dt() const { return dt_; }
  std::chrono::nanoseconds period() const { return period_; }
  // accumulator / period, in [0, 1): how far between two steps the present is.
  double alpha() const;
  std::uint64_t total_steps() const { return total_steps_; }
  std::uint64_t total_dropped_steps() const { return total_dropped_; }
  // When the next step falls due on the clock (for a timer to sleep until).
  Clock::time_point next_step_due() const;

 private:
  const Clock& clock_;
  double dt_;
  std::chrono::nanoseconds period_;
  int max_steps_;
  Clock::time_point last_;
  std::chrono::nanoseconds accumulator_{0};
  std::uint64_t total_steps_ = 0;
  std::uint64_t total_dropped_ = 0;
};

}  // namespace phys
