#pragma once
// The worlds whose goldens the native suites assert (tests/unit/scene_library_test.cpp,
// tests/unit/determinism_test.cpp), run again on a platform without GoogleTest: equal
// hashes there mean that platform reaches the goldens too.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace portable {

struct GoldenWorld {
  std::string name;
  std::function<std::uint64_t()> run;  // the state hash the world ends on
};

std::vector<GoldenWorld> golden_worlds();

}  // namespace portable
