#pragma once
// Clamps the contact solvers compute without a branch. Whether a contact's impulse
// clamps at zero changes from contact to contact in a flowing pile, and the branch
// the compiler made of std::max there was mispredicted about as often as taken
// (docs/ACCURACY.md, "A branchless clamp in the velocity pass").
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
