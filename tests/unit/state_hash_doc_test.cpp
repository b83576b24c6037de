// The state hash's worked example of docs/PROTOCOL.md (section 5.11), read from the
// page and checked against the world's own hash, so that a client in another
// language can compute it from the page alone.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "physics/world.h"
#include "protocol_page.h"

namespace phys::testing {
namespace {

std::string hex64(std::uint64_t v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "0x%016llx", static_cast<unsigned long long>(v));
  return buffer;
}

// Section 5.11 as a client in another language would write it: FNV-1a over bytes,
// each word given least significant byte first.
std::uint64_t fnv1a_over_words(const std::vector<std::uint64_t>& words) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const std::uint64_t word : words) {
    for (int i = 0; i < 8; ++i) {
      h ^= (word >> (8 * i)) & 0xffu;
      h *= 0x100000001b3ull;
    }
  }
  return h;
}

// The example world of section 5.11: a static box floor, then a dynamic circle
// with a velocity and an input. The page lists each body's ten words and the hash;
// the world's own state_hash() must equal the hash of those words, and the page
// must show each of them.
TEST(StateHashDoc, TheExampleOfTheProtocolPage) {
  World world;
  BodyDef floor;
  floor.shape = Shape::Box;
  floor.motion = Motion::Static;
  floor.position = {0.0, -0.5};
  floor.half_extents = {10.0, 0.5};
  BodyDef ball;
  ball.shape = Shape::Circle;
  ball.position = {1.5, 2.0};
  ball.velocity = {3.0, 4.0};
  ball.acceleration = {0.0, 2.5};
  ball.radius = 0.25;
  const BodyId floor_id = world.add_body(floor);
  const BodyId ball_id = world.add_body(ball);
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  // One body a line, its ten words in the page's order.
  // clang-format off
  const std::vector<std::uint64_t> words = {
      floor_id.packed(), 0x001, bits(0.0), bits(-0.5), bits(0.0), bits(0.0), bits(0.0), bits(0.0), bits(10.0), bits(0.5),
      ball_id.packed(),  0x100, bits(1.5), bits(2.0),  bits(3.0), bits(4.0), bits(0.0), bits(2.5), bits(0.25), bits(0.25)};
  // clang-format on
  EXPECT_EQ(fnv1a_over_words(words), world.state_hash());
  const std::string page = protocol_page::text();
  EXPECT_NE(page.find(hex64(world.state_hash())), std::string::npos) << hex64(world.state_hash());
  for (const std::uint64_t word : words) {
    EXPECT_NE(page.find(hex64(word)), std::string::npos) << hex64(word);
  }
}

}  // namespace
}  // namespace phys::testing
