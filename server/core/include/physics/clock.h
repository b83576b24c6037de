#pragma once
// The clock the fixed-timestep driver reads, injectable so tests drive time by hand.
#include <chrono>

namespace phys {

class Clock {
 public:
  using time_point = std::chrono::steady_clock::time_point;
  virtual ~Clock() = default;
  virtual time_point now() const = 0;
};

class SteadyClock final : public Clock {
 public:
  time_point now() const override { return std::chrono::steady_clock::now(); }
};

// Moves only when told to: the fake clock of the tests.
class ManualClock final : public Clock {
 public:
  time_point now() const override { return now_; }
  void advance(std::chrono::nanoseconds by) { now_ += by; }

 private:
  time_point now_{};
};

}  // namespace phys
