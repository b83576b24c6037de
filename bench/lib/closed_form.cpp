#include "closed_form.h"

#include <cmath>

namespace bench {

AxisState closed_form_axis(double x0, double v0, double a, double k, double t) {
  if (k == 0.0) return {x0 + v0 * t + 0.5 * a * t * t, v0 + a * t};
  const double terminal = a / k;
  // 1 - exp(-k t) through expm1, which keeps its digits when k*t is small.
  const double decayed = -std::expm1(-k * t);
  return {x0 + terminal * t + (v0 - terminal) * decayed / k,
          terminal + (v0 - terminal) * (1.0 - decayed)};
}

double apex_through(double y, double vy, double g) { return y + vy * vy / (2.0 * g); }

}  // namespace bench
