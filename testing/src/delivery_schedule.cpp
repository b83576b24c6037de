#include "delivery_schedule.h"

#include <algorithm>

namespace physics_testing {

DeliverySchedule::DeliverySchedule(const PathDirection& path, StallTimeline stalls,
                                   PathRandom jitter_random)
    : path_(path), stalls_(std::move(stalls)), jitter_random_(jitter_random) {}

DeliverySchedule::Delivery DeliverySchedule::schedule(Clock::time_point read_at,
                                                      std::size_t bytes) {
  // Serialisation on the capped link, then propagation: the chunk leaves when the link
  // is free and has been sent n / bandwidth later.
  Clock::time_point sent = read_at;
  if (path_.bandwidth_bytes_per_second > 0.0) {
    const std::chrono::duration<double> on_wire(static_cast<double>(bytes) /
                                                path_.bandwidth_bytes_per_second);
    sent = std::max(read_at, link_free_) + std::chrono::duration_cast<Clock::duration>(on_wire);
    link_free_ = sent;
  }
  Clock::time_point due = sent + path_.latency;
  if (path_.jitter.count() > 0) {
    const auto extra =
        jitter_random_.uniform_up_to(static_cast<std::uint64_t>(path_.jitter.count()));
    due += std::chrono::microseconds(static_cast<std::chrono::microseconds::rep>(extra));
  }
  due = std::max(due, last_due_);
  const StallTimeline::Release release = stalls_.release(due);
  last_due_ = release.at;
  return {release.at, release.stalls_begun};
}

}  // namespace physics_testing
