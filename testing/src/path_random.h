#pragma once
// The link conditioner's random draws: xoshiro256** seeded through splitmix64, with
// its own uniform and exponential draws, so that a seed gives the same jitter and the
// same stall times on every platform (the std distributions differ between standard
// libraries).
#include <array>
#include <cstdint>

namespace physics_testing {

class PathRandom {
 public:
  explicit PathRandom(std::uint64_t seed);
  std::uint64_t next();
  // Uniform in [0, bound], every value equally likely (rejection, no modulo bias).
  std::uint64_t uniform_up_to(std::uint64_t bound);
  // Uniform in [0, 1), from the top 53 bits.
  double unit();
  // Exponential with mean 1 / rate (rate > 0): the gap between Poisson events.
  double exponential(double rate);

 private:
  std::array<std::uint64_t, 4> state_{};
};

}  // namespace physics_testing
