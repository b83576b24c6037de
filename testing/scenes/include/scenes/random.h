#pragma once
// The two fixed generators of the generated scenes: the same numbers on every
// platform and build, for a given seed. Neither is for anything but scenes.
#include <cstdint>

namespace scenes {

// A linear congruential generator (Knuth's MMIX constants) from a fixed state: the
// generator of the rained piles (rained_circles_scene) and of the tests' own rains.
class Rain {
 public:
  // [lo, hi), from the top 53 bits of the state.
  double uniform(double lo, double hi) {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    const double unit = static_cast<double>(state_ >> 11) * 0x1.0p-53;
    return lo + (hi - lo) * unit;
  }

 private:
  std::uint64_t state_ = 12345;
};

// splitmix64: a tiny generator whose output is fixed by the seed, for the
// benchmarks' lattices, velocities and random boxes.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  double uniform(double lo, double hi);  // [lo, hi)

 private:
  std::uint64_t state_;
};

}  // namespace scenes
