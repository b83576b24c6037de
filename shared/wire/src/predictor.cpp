#include "wire/predictor.h"

namespace wire {

Predictor::Predictor(double tick_rate, double gravity_x, double gravity_y)
    : dt_(1.0 / tick_rate), half_dt_squared_((0.5 * dt_) * dt_), gx_(gravity_x), gy_(gravity_y) {}

// The operations and their order are the protocol: PROTOCOL.md 5.2 spells them out
// and its worked example is checked against this function.
void Predictor::advance(PredictedBody& body) const {
  switch (body.mode) {
    case PredictorMode::Ballistic:
      body.x = (body.x + body.vx * dt_) + gx_ * half_dt_squared_;
      body.y = (body.y + body.vy * dt_) + gy_ * half_dt_squared_;
      body.vx = body.vx + gx_ * dt_;
      body.vy = body.vy + gy_ * dt_;
      return;
    case PredictorMode::Glide:
      body.x = body.x + body.vx * dt_;
      body.y = body.y + body.vy * dt_;
      return;
    case PredictorMode::Hold:
      return;
  }
}

}  // namespace wire
