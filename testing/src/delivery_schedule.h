#pragma once
// When each chunk read from one direction of a conditioned path is due at the other
// end: after the bandwidth cap has sent it, the latency and a jitter draw, never
// before the chunk ahead of it (TCP's order), and held to the end of any stall it
// falls in. No sockets and no clock of its own: the caller says when it read.
#include <chrono>
#include <cstddef>
#include <cstdint>

#include "path_random.h"
#include "physics_testing/link_conditioner.h"
#include "stall_timeline.h"

namespace physics_testing {

class DeliverySchedule {
 public:
  using Clock = std::chrono::steady_clock;

  DeliverySchedule(const PathDirection& path, StallTimeline stalls, PathRandom jitter_random);

  struct Delivery {
    Clock::time_point at;
    std::uint64_t stalls_begun;
  };
  // A chunk of `bytes` read at `read_at` (0 bytes: the end of the stream).
  Delivery schedule(Clock::time_point read_at, std::size_t bytes);

  // For chunks read from now on; chunks scheduled already keep their times.
  void set_path(const PathDirection& path) { path_ = path; }
  StallTimeline& stalls() { return stalls_; }

 private:
  PathDirection path_;
  StallTimeline stalls_;
  PathRandom jitter_random_;
  Clock::time_point link_free_{};  // when the capped link has sent what it was given
  Clock::time_point last_due_{};
};

}  // namespace physics_testing
