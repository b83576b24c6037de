// libFuzzer harness: phys::World::from_bytes, fed the bytes a hostile server could
// send as Welcome.world_state. Nothing in them is trusted: bytes that are not a
// world must be refused with a reason, never crash; a world it accepts must step,
// and write bytes that read back to the same world (the same state hash, and the
// same bytes once more).
// Covered: World::from_bytes and its checks, World::to_bytes, and a few steps of
// whatever world passes them. The same entry point runs over the seeds in the gcc
// build (tests/unit/world_bytes_seeds_test.cpp).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "physics/world.h"

namespace {

// Worlds up to this many bodies are stepped: the bytes bound how many bodies a
// world has, but not what a step of a large pile costs, and a slow input is no bug.
constexpr std::size_t kMostBodiesStepped = 2048;
constexpr int kSteps = 3;

// The bytes of `world`, read back: the same world, and the same bytes again.
std::vector<std::uint8_t> round_trip(const phys::World& world) {
  std::vector<std::uint8_t> bytes = world.to_bytes();
  std::string error;
  const std::optional<phys::World> again = phys::World::from_bytes(bytes, &error);
  if (!again.has_value()) std::abort();  // a world's own bytes refused
  if (again->state_hash() != world.state_hash()) std::abort();
  if (again->to_bytes() != bytes) std::abort();
  return bytes;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string error;
  std::optional<phys::World> world =
      phys::World::from_bytes(std::span<const std::uint8_t>(data, size), &error);
  if (!world.has_value()) {
    if (error.empty()) std::abort();  // refused without a reason
    return 0;
  }
  round_trip(*world);
  if (world->body_count() > kMostBodiesStepped) return 0;
  const double dt = 1.0 / 60.0;
  for (int i = 0; i < kSteps; ++i) {
    world->step(dt);
    round_trip(*world);
  }
  return 0;
}
