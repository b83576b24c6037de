// The world_bytes_fuzz harness (tests/fuzz), built here with the core's own
// compiler so that it compiles and holds on every build, not only the clang fuzz
// build: its entry point run over the committed seeds, over the worlds they are made
// from (world_seeds.h) as this core writes them, and over every prefix of those
// bytes, which World::from_bytes must refuse with a reason (the harness aborts on a
// world it accepts that does not step and write itself back).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "physics/world.h"
#include "world_seeds.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace phys::testing {
namespace {

namespace fs = std::filesystem;

std::vector<std::uint8_t> read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void run(const std::vector<std::uint8_t>& bytes) {
  LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
}

TEST(WorldBytesFuzzSeeds, TheCommittedSeedsRunThroughTheHarness) {
  int seeds = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(PHYSICS_FUZZ_CORPUS) / "world_bytes")) {
    run(read_file(entry.path()));
    ++seeds;
  }
  EXPECT_GE(seeds, 3);
}

TEST(WorldBytesFuzzSeeds, TheSeedWorldsAreAcceptedAndReadBackAsTheSameWorld) {
  for (const auto& [name, bytes] : fuzz_seeds::world_seeds()) {
    std::string error;
    const std::optional<World> world = World::from_bytes(bytes, &error);
    ASSERT_TRUE(world.has_value()) << name << ": " << error;
    EXPECT_EQ(world->to_bytes(), bytes) << name;
    run(bytes);
  }
}

TEST(WorldBytesFuzzSeeds, EveryCutWorldIsRefusedWithAReason) {
  for (const auto& [name, bytes] : fuzz_seeds::world_seeds()) {
    std::size_t refused = 0;
    // Every prefix: each one ends inside some field, or between two.
    for (std::size_t n = 0; n < bytes.size(); ++n) {
      const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<long>(n));
      std::string error;
      if (!World::from_bytes(cut, &error).has_value()) {
        ++refused;
        EXPECT_FALSE(error.empty()) << name << " cut at " << n;
      }
      run(cut);
    }
    EXPECT_EQ(refused, bytes.size()) << name << ": a cut world was accepted";
  }
}

}  // namespace
}  // namespace phys::testing
