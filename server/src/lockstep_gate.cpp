#include "server/lockstep_gate.h"

namespace server {

LockstepGate::Decision LockstepGate::decide(bool all_present, bool any_present, time_point now) {
  if (!any_present) {
    // Nobody asked for the next tick yet (or the last waiting client left).
    waiting_since_.reset();
    return Decision::Wait;
  }
  if (all_present) return Decision::Step;
  if (!waiting_since_) waiting_since_ = now;
  if (now - *waiting_since_ >= timeout_) return Decision::StepAfterTimeout;
  return Decision::Wait;
}

std::optional<LockstepGate::time_point> LockstepGate::deadline() const {
  if (!waiting_since_) return std::nullopt;
  return *waiting_since_ + timeout_;
}

}  // namespace server
