#pragma once
// When lockstep may step the next tick: as soon as every joined client has sent its
// input for it, or once `timeout` has passed since the gate began waiting (the first
// input for that tick arrived, or the previous tick stepped, whichever is later).
// With no input at all for the next tick it waits without a deadline, so ticks
// never advance on their own. Time is passed in: tests drive it by hand.
#include <chrono>
#include <optional>

namespace server {

class LockstepGate {
 public:
  using time_point = std::chrono::steady_clock::time_point;

  enum class Decision { Wait, Step, StepAfterTimeout };

  explicit LockstepGate(std::chrono::nanoseconds timeout) : timeout_(timeout) {}

  // all_present: every joined client has an input for the next tick;
  // any_present: at least one has.
  Decision decide(bool all_present, bool any_present, time_point now);
  // Call after the tick stepped: the wait for the following one starts afresh.
  void stepped() { waiting_since_.reset(); }
  // When decide() should be asked again, if the gate is waiting with a deadline.
  std::optional<time_point> deadline() const;
  std::chrono::nanoseconds timeout() const { return timeout_; }

 private:
  std::chrono::nanoseconds timeout_;
  std::optional<time_point> waiting_since_;
};

}  // namespace server
