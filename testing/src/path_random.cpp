#include "path_random.h"

#include <cmath>

namespace physics_testing {

namespace {

std::uint64_t rotate_left(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

PathRandom::PathRandom(std::uint64_t seed) {
  // splitmix64 spreads any seed, 0 included, over xoshiro's state (the seeding its
  // authors recommend); the state is then never all zero.
  for (std::uint64_t& word : state_) {
    std::uint64_t z = (seed += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    word = z ^ (z >> 31);
  }
}

std::uint64_t PathRandom::next() {
  // xoshiro256** (Blackman and Vigna).
  const std::uint64_t result = rotate_left(state_[1] * 5, 7) * 9;
  const std::uint64_t t = state_[1] << 17;
  state_[2] ^= state_[0];
  state_[3] ^= state_[1];
  state_[1] ^= state_[2];
  state_[0] ^= state_[3];
  state_[2] ^= t;
  state_[3] = rotate_left(state_[3], 45);
  return result;
}

std::uint64_t PathRandom::uniform_up_to(std::uint64_t bound) {
  if (bound == UINT64_MAX) return next();
  const std::uint64_t range = bound + 1;
  // The largest multiple of range that fits; draws at or above it are redrawn.
  const std::uint64_t limit = UINT64_MAX - UINT64_MAX % range;
  for (;;) {
    const std::uint64_t x = next();
    if (x < limit) return x % range;
  }
}

double PathRandom::unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

double PathRandom::exponential(double rate) {
  // Inversion: 1 - unit() is in (0, 1], so the log is finite.
  return -std::log(1.0 - unit()) / rate;
}

}  // namespace physics_testing
