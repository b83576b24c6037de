#include "stall_timeline.h"

#include <algorithm>

namespace physics_testing {

namespace {

// A random stall further away than this is never reached (and its time would not fit
// the clock's nanoseconds).
constexpr double kNeverSeconds = 1e9;

}  // namespace

StallTimeline::StallTimeline(const PathStalls& stalls, bool applies, Clock::time_point origin,
                             PathRandom random)
    : origin_(origin), random_(random) {
  reset(stalls, applies, origin);
}

void StallTimeline::reset(const PathStalls& stalls, bool applies, Clock::time_point from) {
  duration_ = applies ? Clock::duration(stalls.duration) : Clock::duration(0);
  every_ = Clock::duration(stalls.every);
  per_second_ = stalls.per_second;
  next_period_ = 1;
  if (every_.count() > 0 && from > origin_) {
    next_period_ = static_cast<std::uint64_t>((from - origin_) / every_);
    while (origin_ + static_cast<Clock::rep>(next_period_) * every_ < from) ++next_period_;
    next_period_ = std::max<std::uint64_t>(next_period_, 1);
  }
  at_.clear();
  for (const std::chrono::milliseconds offset : stalls.at) {
    const Clock::time_point start = origin_ + Clock::duration(offset);
    if (start >= from) at_.push_back(start);
  }
  std::sort(at_.begin(), at_.end());
  next_at_ = 0;
  next_random_.reset();
  if (per_second_ > 0.0) draw_random_after(from);
}

void StallTimeline::draw_random_after(Clock::time_point after) {
  const double seconds = random_.exponential(per_second_);
  if (seconds > kNeverSeconds) {
    next_random_.reset();
    return;
  }
  next_random_ =
      after + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

std::optional<StallTimeline::Clock::time_point> StallTimeline::next_start() const {
  std::optional<Clock::time_point> next;
  const auto consider = [&](Clock::time_point start) {
    if (!next || start < *next) next = start;
  };
  if (every_.count() > 0) consider(origin_ + static_cast<Clock::rep>(next_period_) * every_);
  if (next_at_ < at_.size()) consider(at_[next_at_]);
  if (next_random_) consider(*next_random_);
  return next;
}

void StallTimeline::pop_next() {
  const std::optional<Clock::time_point> next = next_start();
  if (!next) return;
  // One source at a time: two stalls at the same instant are two stalls.
  if (every_.count() > 0 && origin_ + static_cast<Clock::rep>(next_period_) * every_ == *next) {
    ++next_period_;
  } else if (next_at_ < at_.size() && at_[next_at_] == *next) {
    ++next_at_;
  } else if (next_random_ == next) {
    draw_random_after(*next);
  }
}

StallTimeline::Release StallTimeline::release(Clock::time_point due) {
  Release release{due, 0};
  if (duration_.count() <= 0) return release;
  // The settings keep stalls from covering the whole line (every > duration; a random
  // rate below one per duration), so this ends.
  for (std::optional<Clock::time_point> start = next_start(); start && *start <= release.at;
       start = next_start()) {
    pop_next();
    ++release.stalls_begun;
    release.at = std::max(release.at, *start + duration_);
  }
  return release;
}

}  // namespace physics_testing
