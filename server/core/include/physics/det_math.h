#pragma once
// exp, expm1 and log built only from IEEE-754 operations that every platform rounds
// alike (+, -, *, / on doubles, conversions between double and int, and setting a
// double's exponent bits), so that the step gives the same doubles on x86-64,
// AArch64 and WebAssembly. The C library's functions are not required to round
// alike everywhere (glibc, Apple's libm, Microsoft's CRT and musl differ in the
// last bit on some arguments); these do, given -ffp-contract=off (no fused
// multiply-add), which every target of ours is built with.
//
// The methods are fdlibm's (Sun, 1993: e_exp.c, s_expm1.c's reduction, e_log.c),
// with its minimax coefficients: argument reduction by n*ln2 split in two parts
// (ln2_hi has 21 trailing zero bits, so n*ln2_hi is exact for |n| < 2^11), then a
// rational approximation on [-ln2/2, ln2/2] (exp, expm1) or on [sqrt(2)/2, sqrt(2)]
// (log). Error against the C library over a million points of each range the
// core uses (tests/unit/det_math_test.cpp states and asserts it): exp <= 1 ulp,
// expm1 <= 1 ulp for x <= 0 (2 ulp just above ln2/2), log <= 1 ulp; glibc itself is
// within 1 ulp of the exact value. Subnormal results are rounded once, the same way
// everywhere.
#include <cstdint>
#include <cstring>
#include <limits>

namespace phys::det {

namespace detail {

inline std::uint64_t bits_of(double x) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}
inline double from_bits(std::uint64_t bits) {
  double x = 0.0;
  std::memcpy(&x, &bits, sizeof x);
  return x;
}
// 2^n, exactly, for n in [-1022, 1023].
inline double pow2(int n) { return from_bits(static_cast<std::uint64_t>(n + 1023) << 52); }
// y * 2^n for y in [0.5, 2] and n in [-1100, 1100]: exact while the result is
// normal; a subnormal result is rounded once (by the last multiplication).
inline double scale(double y, int n) {
  if (n > 1023) return y * pow2(1023) * pow2(n - 1023);
  if (n < -1022) return y * pow2(n + 1000) * pow2(-1000);
  return y * pow2(n);
}

inline constexpr double kLn2Hi = 6.93147180369123816490e-01;  // 0x3fe62e42fee00000
inline constexpr double kLn2Lo = 1.90821492927058770002e-10;  // 0x3dea39ef35793c76
inline constexpr double kInvLn2 = 1.44269504088896338700e+00;
inline constexpr double kHalfLn2 = 3.46573590279972654709e-01;
// The largest x with a finite exp(x), and the smallest with a non-zero one.
inline constexpr double kExpOverflow = 7.09782712893383973096e+02;
inline constexpr double kExpUnderflow = -7.45133219101941108420e+02;

// n = round(x / ln2) and r = x - n*ln2 as hi - lo (hi exact); n = 0 inside
// [-ln2/2, ln2/2], where x itself is taken.
struct Reduced {
  int n = 0;
  double hi = 0.0;
  double lo = 0.0;
};
inline Reduced reduce(double x) {
  if (!(x > kHalfLn2 || x < -kHalfLn2)) return {0, x, 0.0};
  const int n = static_cast<int>(kInvLn2 * x + (x < 0.0 ? -0.5 : 0.5));
  const double dn = static_cast<double>(n);
  return {n, x - dn * kLn2Hi, dn * kLn2Lo};
}

// c(r) = r - r^2 (P1 + P2 r^2 + ... + P5 r^8), so that exp(r) = 1 + r + r c / (2 - c)
// with an error below 2^-59 on [-ln2/2, ln2/2] (fdlibm's Remez coefficients).
inline double exp_c(double r) {
  constexpr double kP1 = 1.66666666666666019037e-01;
  constexpr double kP2 = -2.77777777770155933842e-03;
  constexpr double kP3 = 6.61375632143793436117e-05;
  constexpr double kP4 = -1.65339022054652515390e-06;
  constexpr double kP5 = 4.13813679705723846039e-08;
  const double r2 = r * r;
  return r - r2 * (kP1 + r2 * (kP2 + r2 * (kP3 + r2 * (kP4 + r2 * kP5))));
}

}  // namespace detail

// e^x. exp(NaN) = NaN, exp(+inf) = +inf, exp(-inf) = 0.
inline double exp(double x) {
  using namespace detail;
  if (x != x) return x;
  if (x > kExpOverflow) return std::numeric_limits<double>::infinity();
  if (x < kExpUnderflow) return 0.0;
  if (x < 0x1p-28 && x > -0x1p-28) return 1.0 + x;  // exact to rounding: e^x - 1 - x < 2^-57
  const Reduced red = reduce(x);
  const double r = red.hi - red.lo;
  const double c = exp_c(r);
  if (red.n == 0) return 1.0 - ((r * c) / (c - 2.0) - r);
  const double y = 1.0 - ((red.lo - (r * c) / (2.0 - c)) - red.hi);
  return scale(y, red.n);
}

// e^x - 1, accurate for small |x| where exp(x) - 1 would cancel. expm1(NaN) = NaN,
// expm1(+inf) = +inf, expm1(-inf) = -1.
inline double expm1(double x) {
  using namespace detail;
  if (x != x) return x;
  if (x > kExpOverflow) return std::numeric_limits<double>::infinity();
  if (x < -40.0) return -1.0;  // e^-40 < 2^-57: -1 is the rounded result
  if (x < 0x1p-54 && x > -0x1p-54) return x;
  const Reduced red = reduce(x);
  const double r = red.hi - red.lo;
  // e^r - 1 = r + r c / (2 - c), then the rounding of r = hi - lo carried
  // (e^(r + e) - 1 = (e^r - 1) + e^r e for the tiny e).
  const double c = exp_c(r);
  double small = r + (r * c) / (2.0 - c);
  if (red.n == 0) return small;
  const double rounding_of_r = (red.hi - r) - red.lo;
  small = small + (small + 1.0) * rounding_of_r;
  // e^x - 1 = 2^n (e^r - 1) + (2^n - 1); 2^n - 1 is exact for |n| <= 53 and its
  // rounding no longer matters beyond.
  if (red.n > 1023) return scale(small + 1.0, red.n);
  const double two_n = pow2(red.n);
  return scale(small, red.n) + (two_n - 1.0);
}

// The natural logarithm. log(0) = -inf, log(x < 0) = NaN, log(+inf) = +inf.
inline double log(double x) {
  using namespace detail;
  if (x != x) return x;
  if (x < 0.0) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0.0) return -std::numeric_limits<double>::infinity();
  if (x == std::numeric_limits<double>::infinity()) return x;
  int k = 0;
  std::uint64_t bits = bits_of(x);
  if (bits < (std::uint64_t{1} << 52)) {  // subnormal: scale into the normal range
    bits = bits_of(x * 0x1p54);
    k = -54;
  }
  constexpr std::uint64_t kMantissa = (std::uint64_t{1} << 52) - 1;
  constexpr std::uint64_t kSqrt2Mantissa = 0x6a09e667f3bcdULL;  // sqrt(2) = 1.6a09e667f3bcd * 2^0
  const std::uint64_t mantissa = bits & kMantissa;
  k += static_cast<int>(bits >> 52) - 1023;
  // x = 2^k * m with m in [sqrt(2)/2, sqrt(2)); f = m - 1 is exact (Sterbenz).
  double m = 0.0;
  if (mantissa >= kSqrt2Mantissa) {
    m = from_bits(mantissa | (std::uint64_t{1022} << 52));
    k += 1;
  } else {
    m = from_bits(mantissa | (std::uint64_t{1023} << 52));
  }
  const double f = m - 1.0;
  // log(1 + f) = f - f^2/2 + s (f^2/2 + R(s^2)) with s = f / (2 + f), R fdlibm's
  // minimax polynomial (error below 2^-58.45).
  constexpr double kLg1 = 6.666666666666735130e-01;
  constexpr double kLg2 = 3.999999999940941908e-01;
  constexpr double kLg3 = 2.857142874366239149e-01;
  constexpr double kLg4 = 2.222219843214978396e-01;
  constexpr double kLg5 = 1.818357216161805012e-01;
  constexpr double kLg6 = 1.531383769920937332e-01;
  constexpr double kLg7 = 1.479819860511658591e-01;
  const double s = f / (2.0 + f);
  const double z = s * s;
  const double w = z * z;
  const double t1 = w * (kLg2 + w * (kLg4 + w * kLg6));
  const double t2 = z * (kLg1 + w * (kLg3 + w * (kLg5 + w * kLg7)));
  const double r = t2 + t1;
  const double half_f_squared = 0.5 * f * f;
  const double dk = static_cast<double>(k);
  return dk * kLn2Hi - ((half_f_squared - (s * (half_f_squared + r) + dk * kLn2Lo)) - f);
}

}  // namespace phys::det
