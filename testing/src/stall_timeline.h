#pragma once
// When one direction of a conditioned path stalls: the periodic, scripted and random
// stalls of PathStalls merged into one timeline, in delivery time. Bytes due while a
// stall lasts are held to its end, as a TCP receiver sees nothing between a lost
// segment and its retransmission, then everything at once.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "path_random.h"
#include "physics_testing/link_conditioner.h"

namespace physics_testing {

class StallTimeline {
 public:
  using Clock = std::chrono::steady_clock;

  // The stalls of `stalls` (none when `applies` is false) on a connection that began
  // at `origin`; `random` draws the random stalls' times.
  StallTimeline(const PathStalls& stalls, bool applies, Clock::time_point origin,
                PathRandom random);

  // From `from` on, the stalls of `stalls` instead (those that begin at or after
  // `from`); the random draws continue from where they were.
  void reset(const PathStalls& stalls, bool applies, Clock::time_point from);

  struct Release {
    Clock::time_point at;        // `due`, or the end of the stall that holds it
    std::uint64_t stalls_begun;  // stalls whose start this call passed
  };
  // When bytes due at `due` (not earlier than any due before) can be delivered.
  Release release(Clock::time_point due);

 private:
  std::optional<Clock::time_point> next_start() const;
  void pop_next();
  void draw_random_after(Clock::time_point after);

  Clock::time_point origin_;
  Clock::duration duration_{0};
  Clock::duration every_{0};
  std::uint64_t next_period_ = 1;      // the next periodic stall: origin + k * every
  std::vector<Clock::time_point> at_;  // scripted starts, sorted
  std::size_t next_at_ = 0;
  double per_second_ = 0.0;
  std::optional<Clock::time_point> next_random_;
  PathRandom random_;
};

}  // namespace physics_testing
