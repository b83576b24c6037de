#pragma once
// The velocity pass's clamp of an impulse at zero, without a branch. Whether a
// contact's impulse clamps changes from contact to contact in a flowing pile; the
// compiler made std::max a branch there, and the profile put the most samples of
// the pass just after it (docs/PHYSICS.md, "Velocities: sequential impulses").
#include <algorithm>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace phys {

// std::max(x, 0.0), bit for bit (NaN and -0 included).
inline double at_least_zero(double x) {
#if defined(__SSE2__)
  // maxsd(a, b) is a > b ? a : b, as std::max(x, 0.0) is 0.0 > x ? 0.0 : x.
  return _mm_cvtsd_f64(_mm_max_sd(_mm_set_sd(0.0), _mm_set_sd(x)));
#else
  return std::max(x, 0.0);
#endif
}

}  // namespace phys
