#pragma once
// The dead-reckoning predictor both ends run (docs/PROTOCOL.md, section 5.2). The
// client advances the bodies it was sent with it to draw them between updates; the
// server advances its copy of what each client holds with the very same code, so it
// knows that copy bit for bit. Plain IEEE-754 doubles, one rounding per operation
// (built with -ffp-contract=off), no library functions: a client in any language
// that does the same operations in the same order gets the same bits.
#include <cstdint>

namespace wire {

// How a body's state is carried from one tick to the next.
enum class PredictorMode : std::uint8_t {
  Ballistic = 0,  // under the scene's gravity: free flight
  Glide = 1,      // at constant velocity: sliding or rolling on a support
  Hold = 2,       // not at all: at rest or asleep
};
inline constexpr std::uint32_t kPredictorModeCount = 3;

struct PredictedBody {
  std::uint64_t id = 0;
  double x = 0.0;
  double y = 0.0;
  double vx = 0.0;
  double vy = 0.0;
  PredictorMode mode = PredictorMode::Ballistic;
};

class Predictor {
 public:
  Predictor() = default;
  // dt = 1 / tick_rate, as Welcome gives the tick rate.
  Predictor(double tick_rate, double gravity_x, double gravity_y);

  // One tick: Ballistic  x += v*dt + g*(dt*dt/2), v += g*dt;  Glide  x += v*dt;
  // Hold  nothing.
  void advance(PredictedBody& body) const;

  double dt() const { return dt_; }

 private:
  double dt_ = 0.0;
  double half_dt_squared_ = 0.0;  // (0.5 * dt) * dt
  double gx_ = 0.0;
  double gy_ = 0.0;
};

}  // namespace wire
