#include "token_bucket.h"

#include <algorithm>
#include <cmath>

namespace server {

TokenBucket::TokenBucket(double rate_per_second, double burst, clock::time_point now)
    : rate_(rate_per_second), burst_(std::max(burst, 1.0)), balance_(burst_), updated_(now) {}

void TokenBucket::refill(clock::time_point now) {
  if (now <= updated_) return;
  const double seconds = std::chrono::duration<double>(now - updated_).count();
  balance_ = std::min(burst_, balance_ + seconds * rate_);
  updated_ = now;
}

void TokenBucket::spend(double tokens, clock::time_point now) {
  if (unlimited()) return;
  refill(now);
  balance_ -= tokens;
}

bool TokenBucket::in_debt(clock::time_point now) { return balance(now) < 0.0; }

double TokenBucket::balance(clock::time_point now) {
  if (unlimited()) return burst_;
  refill(now);
  return balance_;
}

TokenBucket::clock::duration TokenBucket::wait(clock::time_point now) {
  const double owed = -balance(now);
  if (owed <= 0.0) return clock::duration::zero();
  // Rounded up, so that after the wait the balance is at zero or above.
  const auto wait = std::chrono::duration<double>(owed / rate_);
  return std::chrono::ceil<clock::duration>(wait) + clock::duration(1);
}

}  // namespace server
