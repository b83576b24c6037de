#pragma once
// Adds the wall time of a scope to a phase of the step's profile, when profiling
// is on (and reads no clock when it is off).
#include <chrono>

namespace phys {

class PhaseTimer {
 public:
  PhaseTimer(bool on, double& into) : on_(on), into_(into) {
    if (on_) start_ = std::chrono::steady_clock::now();
  }
  ~PhaseTimer() {
    if (on_) {
      into_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
  }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  bool on_;
  double& into_;
  std::chrono::steady_clock::time_point start_{};
};

}  // namespace phys
