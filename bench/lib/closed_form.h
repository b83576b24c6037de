#pragma once
// Closed forms the report measures against.

namespace bench {

struct AxisState {
  double position;
  double velocity;
};

// dv/dt = a - k*v on one axis from (x0, v0), after t seconds. k = 0 is the parabola
// x0 + v0*t + a*t^2/2; otherwise v = a/k + (v0 - a/k)*exp(-k*t) and x its integral.
AxisState closed_form_axis(double x0, double v0, double a, double k, double t);

// Apex height of a free flight through height y with upward speed vy under gravity g
// (> 0): y + vy^2 / (2g). Exact for the continuous parabola through the sampled state.
double apex_through(double y, double vy, double g);

}  // namespace bench
