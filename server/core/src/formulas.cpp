#include "physics/formulas.h"

namespace phys {

// The per-body and per-pair formulas are inline in the header; what is left here
// runs rarely.

bool apply_restitution(Vec2& v1, double inv_mass1, Vec2& v2, double inv_mass2, Vec2 n,
                       double restitution, double rest_speed) {
  const double inv_sum = inv_mass1 + inv_mass2;
  if (inv_sum <= 0.0) return false;
  const double closing = dot(v2 - v1, n);  // < 0: approaching
  if (closing >= 0.0) return false;
  const double e = effective_restitution(-closing, restitution, rest_speed);
  const double impulse = -(1.0 + e) * closing / inv_sum;
  v1 -= n * (impulse * inv_mass1);
  v2 += n * (impulse * inv_mass2);
  return true;
}

}  // namespace phys
