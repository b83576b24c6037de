// The uniform grid against brute force on many random scenes (mixed sizes, huge
// boxes, negative coordinates, far from the origin), and its output order fixed
// by the inputs alone. Also the test support's own pair finder (sweep_pairs, which
// the overlap measure of the stability bounds uses instead of the grid) against an
// all-pairs loop written here.
#include "physics/broadphase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "physics_test_support.h"

namespace phys {
namespace {

struct SceneShape {
  const char* name;
  int count;
  Vec2 centre;    // where the scene sits
  double spread;  // half width of the region the boxes are scattered in
  double small;   // typical half size
  double huge;    // half size of the occasional huge box
  double huge_share;
};

// Uniform doubles from a fixed-seed engine, by hand rather than through
// std::uniform_real_distribution, whose output differs between standard libraries.
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double between(double lo, double hi) { return lo + (hi - lo) * unit(); }

 private:
  std::mt19937_64 engine_;
};

std::vector<Aabb> random_scene(const SceneShape& shape, std::uint64_t seed) {
  Random random(seed);
  std::vector<Aabb> boxes;
  for (int i = 0; i < shape.count; ++i) {
    const Vec2 c{shape.centre.x + random.between(-shape.spread, shape.spread),
                 shape.centre.y + random.between(-shape.spread, shape.spread)};
    const bool huge = random.unit() < shape.huge_share;
    const double scale = huge ? shape.huge : shape.small;
    const Vec2 h{scale * random.between(0.05, 1.0), scale * random.between(0.05, 1.0)};
    boxes.push_back({c - h, c + h});
  }
  // Some exactly touching pairs: touching counts as overlapping.
  for (int i = 0; i + 1 < shape.count && i < 20; i += 2) {
    const Aabb a = boxes[static_cast<std::size_t>(i)];
    const double w = a.max.x - a.min.x;
    boxes[static_cast<std::size_t>(i) + 1] = {{a.max.x, a.min.y}, {a.max.x + w, a.max.y}};
  }
  return boxes;
}

std::vector<BodyPair> sorted(std::vector<BodyPair> pairs) {
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

const SceneShape kShapes[] = {
    {"small_uniform", 500, {0.0, 0.0}, 50.0, 0.5, 0.5, 0.0},
    {"dense", 800, {0.0, 0.0}, 10.0, 0.5, 0.5, 0.0},
    {"mixed_sizes", 600, {0.0, 0.0}, 80.0, 0.3, 6.0, 0.1},
    {"huge_boxes", 400, {0.0, 0.0}, 100.0, 0.5, 200.0, 0.02},
    {"negative_coordinates", 500, {-350.0, -720.0}, 40.0, 0.7, 3.0, 0.05},
    {"far_from_origin", 500, {100000.0, -100000.0}, 60.0, 0.5, 5.0, 0.05},
    {"very_far_sparse", 300, {1.0e7, 1.0e7}, 1.0e4, 0.5, 50.0, 0.05},
    {"single_box", 1, {0.0, 0.0}, 1.0, 0.5, 0.5, 0.0},
    {"empty", 0, {0.0, 0.0}, 1.0, 0.5, 0.5, 0.0},
};

class GridAgainstBruteForce : public ::testing::TestWithParam<SceneShape> {};

TEST_P(GridAgainstBruteForce, FindsExactlyTheSamePairsOnRandomScenes) {
  UniformGrid grid;  // reused across scenes on purpose: no state may leak
  for (std::uint64_t seed = 1; seed <= 25; ++seed) {
    const std::vector<Aabb> boxes = random_scene(GetParam(), seed);
    std::vector<BodyPair> expected;
    std::vector<BodyPair> actual;
    find_pairs_brute_force(boxes, expected);
    grid.find_pairs(boxes, actual);
    // Each pair once, smaller index first.
    for (const BodyPair& pair : actual) ASSERT_LT(pair.a, pair.b) << "seed " << seed;
    const std::set<BodyPair> unique(actual.begin(), actual.end());
    ASSERT_EQ(unique.size(), actual.size()) << "duplicate pairs, seed " << seed;
    ASSERT_EQ(sorted(actual), sorted(expected)) << "seed " << seed;
  }
}

TEST_P(GridAgainstBruteForce, QueriesAgainstTargetsFindTheSamePairs) {
  UniformGrid grid;
  for (std::uint64_t seed = 100; seed < 110; ++seed) {
    const std::vector<Aabb> targets = random_scene(GetParam(), seed);
    SceneShape query_shape = GetParam();
    query_shape.count = std::min(query_shape.count, 60);
    const std::vector<Aabb> queries = random_scene(query_shape, seed + 1000);
    std::vector<BodyPair> expected;
    for (std::uint32_t q = 0; q < queries.size(); ++q) {
      for (std::uint32_t t = 0; t < targets.size(); ++t) {
        const Aabb& a = queries[q];
        const Aabb& b = targets[t];
        if (a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y) {
          expected.push_back({q, t});
        }
      }
    }
    std::vector<BodyPair> actual;
    grid.find_pairs_between(queries, targets, actual);
    ASSERT_EQ(sorted(actual), sorted(expected)) << "seed " << seed;
  }
}

TEST_P(GridAgainstBruteForce, OrderDependsOnlyOnTheInputs) {
  const std::vector<Aabb> boxes = random_scene(GetParam(), 7);
  // The same boxes at another address, found by a fresh grid and by a grid that
  // has seen other scenes: the same pairs in the same order.
  const std::vector<Aabb> copy(boxes.begin(), boxes.end());
  UniformGrid fresh;
  UniformGrid used;
  std::vector<BodyPair> scratch;
  used.find_pairs(random_scene(GetParam(), 8), scratch);
  used.find_pairs(random_scene(kShapes[3], 9), scratch);
  std::vector<BodyPair> first;
  std::vector<BodyPair> second;
  std::vector<BodyPair> third;
  fresh.find_pairs(boxes, first);
  used.find_pairs(copy, second);
  fresh.find_pairs(boxes, third);
  EXPECT_EQ(first, second);
  EXPECT_EQ(first, third);
}

INSTANTIATE_TEST_SUITE_P(Scenes, GridAgainstBruteForce, ::testing::ValuesIn(kShapes),
                         [](const auto& case_info) { return std::string(case_info.param.name); });

TEST(BruteForce, HandCheckedPairs) {
  // 0 and 1 overlap, 1 and 2 touch, 3 is alone: pairs (0,1) and (1,2).
  const std::vector<Aabb> boxes{{{0.0, 0.0}, {2.0, 2.0}},
                                {{1.0, 1.0}, {3.0, 3.0}},
                                {{3.0, 0.0}, {4.0, 1.0}},
                                {{10.0, 10.0}, {11.0, 11.0}}};
  std::vector<BodyPair> pairs{{9, 9}};  // cleared first
  find_pairs_brute_force(boxes, pairs);
  EXPECT_EQ(sorted(pairs), (std::vector<BodyPair>{{0, 1}, {1, 2}}));
  UniformGrid grid;
  grid.find_pairs(boxes, pairs);
  EXPECT_EQ(sorted(pairs), (std::vector<BodyPair>{{0, 1}, {1, 2}}));
}

// The grid's build ends whatever boxes it is given: centres at plus and minus the
// largest double (a spread no double holds) and far from the origin; the pairs are
// still exact.
TEST(UniformGridBuild, EndsOnSpreadsNoDoubleHolds) {
  constexpr double kHuge = 1.0e308;
  const std::vector<Aabb> boxes{{{-kHuge - 1.0, 0.0}, {-kHuge + 1.0, 1.0}},
                                {{kHuge - 1.0, 0.0}, {kHuge + 1.0, 1.0}},
                                {{0.0, 0.0}, {1.0, 1.0}},
                                {{0.5, 0.5}, {1.5, 1.5}},
                                {{1.0e12, -1.0e12}, {1.0e12 + 1.0, -1.0e12 + 1.0}}};
  std::vector<BodyPair> expected;
  find_pairs_brute_force(boxes, expected);
  UniformGrid grid;
  std::vector<BodyPair> pairs;
  grid.find_pairs(boxes, pairs);
  EXPECT_EQ(sorted(pairs), sorted(expected));
  EXPECT_EQ(sorted(pairs), (std::vector<BodyPair>{{2, 3}}));
}

// Every pair of boxes that meet, by looking at all n(n-1)/2 of them: the oracle of
// the test support's sweep, sharing no code with it nor with the core.
std::vector<testing::IndexPair> all_meeting_pairs(const std::vector<Aabb>& boxes) {
  std::vector<testing::IndexPair> pairs;
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    for (std::uint32_t j = i + 1; j < boxes.size(); ++j) {
      const Aabb& a = boxes[i];
      const Aabb& b = boxes[j];
      if (a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y) {
        pairs.push_back({i, j});
      }
    }
  }
  return pairs;
}

class SweepAgainstAllPairs : public ::testing::TestWithParam<SceneShape> {};

TEST_P(SweepAgainstAllPairs, FindsExactlyTheSamePairs) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const std::vector<Aabb> boxes = random_scene(GetParam(), seed);
    std::vector<testing::IndexPair> swept = testing::sweep_pairs(boxes);
    for (const testing::IndexPair& pair : swept) ASSERT_LT(pair.a, pair.b) << "seed " << seed;
    std::sort(swept.begin(), swept.end());
    ASSERT_EQ(swept, all_meeting_pairs(boxes)) << "seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, SweepAgainstAllPairs, ::testing::ValuesIn(kShapes),
                         [](const auto& case_info) { return std::string(case_info.param.name); });

TEST(SweepPairs, HandCheckedPairs) {
  // As BruteForce.HandCheckedPairs, with a box 4 spanning them all on x but not on
  // y (the sweep must pass over it): pairs (0,1), (1,2) and, touching 3 on y, (3,4).
  const std::vector<Aabb> boxes{{{0.0, 0.0}, {2.0, 2.0}},
                                {{1.0, 1.0}, {3.0, 3.0}},
                                {{3.0, 0.0}, {4.0, 1.0}},
                                {{10.0, 10.0}, {11.0, 11.0}},
                                {{-5.0, 11.0}, {20.0, 12.0}}};
  std::vector<testing::IndexPair> pairs = testing::sweep_pairs(boxes);
  std::sort(pairs.begin(), pairs.end());
  EXPECT_EQ(pairs, (std::vector<testing::IndexPair>{{0, 1}, {1, 2}, {3, 4}}));
}

// The overlap measure by hand: circles of radius 0.5 whose centres are 0.9 m apart
// overlap by 0.1 m; a circle whose centre is 0.45 m above a box's top (r = 0.5)
// sinks 0.05 m into it; two static boxes overlapping by 0.5 m do not count.
TEST(MaxOverlap, HandComputedScene) {
  std::vector<BodyState> bodies(6);
  const auto circle = [](BodyState& b, Vec2 at) {
    b.shape = Shape::Circle;
    b.motion = Motion::Dynamic;
    b.radius = 0.5;
    b.position = at;
  };
  const auto box = [](BodyState& b, Vec2 at, Vec2 half) {
    b.shape = Shape::Box;
    b.motion = Motion::Static;
    b.half_extents = half;
    b.position = at;
  };
  circle(bodies[0], {100.0, 0.0});
  circle(bodies[1], {100.9, 0.0});
  box(bodies[2], {0.0, -0.5}, {1.0, 0.5});
  circle(bodies[3], {0.0, 0.45});
  box(bodies[4], {-50.0, 0.0}, {1.0, 1.0});
  box(bodies[5], {-48.5, 0.0}, {1.0, 1.0});
  EXPECT_NEAR(testing::max_overlap(bodies), 0.1, 1e-12);
  bodies[1].position.x = 101.5;  // now apart: the circle on the box is the deepest
  EXPECT_NEAR(testing::max_overlap(bodies), 0.05, 1e-12);
}

TEST(UniformGrid, ClearsTheOutputFirst) {
  UniformGrid grid;
  std::vector<BodyPair> pairs{{1, 2}, {3, 4}};
  const std::vector<Aabb> apart{{{0.0, 0.0}, {1.0, 1.0}}, {{5.0, 5.0}, {6.0, 6.0}}};
  grid.find_pairs(apart, pairs);
  EXPECT_TRUE(pairs.empty());
}

}  // namespace
}  // namespace phys
