#include "timeline.h"

#include <algorithm>
#include <stdexcept>

#include "timing.h"

namespace bench {

std::vector<TimelineWindow> timeline_windows(std::span<const double> wall_seconds,
                                             std::span<const double> cpu_seconds,
                                             std::span<const std::size_t> awake_after,
                                             int window_steps, double dt) {
  if (window_steps < 1) throw std::invalid_argument("timeline window must be at least one step");
  if (cpu_seconds.size() != wall_seconds.size()) {
    throw std::invalid_argument("timeline: wall and CPU times differ in length");
  }
  const auto window = static_cast<std::size_t>(window_steps);
  const std::size_t count = (wall_seconds.size() + window - 1) / window;
  if (awake_after.size() != count) {
    throw std::invalid_argument("timeline: one awake count per window expected");
  }
  std::vector<TimelineWindow> windows;
  windows.reserve(count);
  for (std::size_t w = 0; w < count; ++w) {
    const std::size_t first = w * window;
    const std::size_t steps = std::min(window, wall_seconds.size() - first);
    TimelineWindow out;
    out.end_s = static_cast<double>(first + steps) * dt;
    out.steps = steps;
    out.awake = awake_after[w];
    out.ms_mean = mean_ms(wall_seconds.subspan(first, steps));
    out.cpu_ms_mean = mean_ms(cpu_seconds.subspan(first, steps));
    windows.push_back(out);
  }
  return windows;
}

}  // namespace bench
