// The relay follower's fuzz entry point (tests/fuzz/relay_follow_target.h) in the
// ordinary build: over the seeds it makes, which must be the committed corpus
// (tests/fuzz/corpus/relay_follow/), and over each seed cut short and with bytes
// flipped. A crash or a broken invariant aborts the test.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "relay_follow_target.h"

namespace {

std::set<std::string> committed_seeds() {
  std::set<std::string> seeds;
  for (const auto& entry : std::filesystem::directory_iterator(PHYSICS_RELAY_CORPUS_DIR)) {
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    seeds.insert(bytes.str());
  }
  return seeds;
}

void run(const std::string& input) {
  relay_fuzz::run_one(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
}

TEST(RelayFollowFuzzSeeds, TheCommittedCorpusIsTheSeedsMade) {
  const std::vector<std::string> made = relay_fuzz::make_seeds();
  ASSERT_FALSE(made.empty());
  EXPECT_EQ(committed_seeds(), std::set<std::string>(made.begin(), made.end()))
      << "rewrite tests/fuzz/corpus/relay_follow/ (scripts/test-fuzz.sh --seeds)";
}

TEST(RelayFollowFuzzSeeds, EverySeedCutAndFlippedRunsClean) {
  for (const std::string& seed : committed_seeds()) {
    run(seed);
    for (std::size_t cut = 0; cut < seed.size(); cut += 7) run(seed.substr(0, cut));
    for (std::size_t at = 1; at < seed.size(); at += 3) {
      std::string flipped = seed;
      flipped[at] = static_cast<char>(flipped[at] ^ 0x5A);
      run(flipped);
    }
  }
}

}  // namespace
