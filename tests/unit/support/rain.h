#pragma once
// A fixed linear congruential generator (Knuth's MMIX constants) for rained scenes:
// the same rain on every platform and build. Free of GoogleTest, so that the
// physics-settle tool (bench/settle) rains exactly the tests' piles.
#include <cstdint>

namespace phys::testing {

class Rain {
 public:
  double uniform(double lo, double hi) {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    const double unit = static_cast<double>(state_ >> 11) * 0x1.0p-53;
    return lo + (hi - lo) * unit;
  }

 private:
  std::uint64_t state_ = 12345;
};

}  // namespace phys::testing
