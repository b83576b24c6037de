#pragma once
// A run's cost over simulated time: the mean time per step and the awake bodies in
// windows of a fixed number of steps. A whole-run mean hides when the cost is paid
// (a pile that flows for 5 s or for 15 s, then sleeps); the timeline shows it, for
// ours and the peers alike.
#include <cstddef>
#include <span>
#include <vector>

namespace bench {

struct TimelineWindow {
  double end_s = 0.0;        // simulated time at the window's last step
  std::size_t steps = 0;     // steps in the window (the last may be shorter)
  std::size_t awake = 0;     // awake dynamic bodies after its last step
  double ms_mean = 0.0;      // wall time per step
  double cpu_ms_mean = 0.0;  // thread CPU time per step
};

// Splits per-step times into windows of `window_steps` (the last window takes what
// is left). `awake_after` holds the awake count after each window's last step, one
// per window. Seconds in, milliseconds out.
std::vector<TimelineWindow> timeline_windows(std::span<const double> wall_seconds,
                                             std::span<const double> cpu_seconds,
                                             std::span<const std::size_t> awake_after,
                                             int window_steps, double dt);

}  // namespace bench
