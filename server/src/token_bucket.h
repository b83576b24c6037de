#pragma once
// A token bucket: `rate` tokens a second flow in, up to `burst` held. Spending may
// overdraw it (a read's bytes are known only once they have arrived); while it is
// in debt the caller waits wait() before costing us more. No clock of its own: the
// caller passes the time, so tests drive it directly.
#include <chrono>

namespace server {

class TokenBucket {
 public:
  using clock = std::chrono::steady_clock;

  // Starts full. rate <= 0 means unlimited.
  TokenBucket(double rate_per_second, double burst, clock::time_point now);

  void spend(double tokens, clock::time_point now);
  // True while the balance is below zero.
  bool in_debt(clock::time_point now);
  // How long until the balance is back at zero (zero when it is not in debt).
  clock::duration wait(clock::time_point now);
  double balance(clock::time_point now);
  bool unlimited() const { return rate_ <= 0.0; }

 private:
  void refill(clock::time_point now);

  double rate_;
  double burst_;
  double balance_;
  clock::time_point updated_;
};

}  // namespace server
