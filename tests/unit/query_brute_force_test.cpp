// The world's queries against brute force: random scenes of circles and boxes,
// static, dynamic and kinematic, some sensors, some filtered, some far larger than
// the rest (kept out of the grids' cells), stepped so that they move; then hundreds
// of random queries of each kind, each answer compared with every body tested one
// by one (the exact tests of physics/query.h, with the filter and sensor rules):
// nothing missed, nothing extra, the same order, the same numbers. On a lattice,
// bodies and queries meet exactly at their boundaries often. Then bodies are added,
// removed and moved, and the answers checked again.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "physics/query.h"
#include "physics_test_support.h"
#include "scenes/random.h"
#include "scenes/scenes.h"

namespace phys::testing {
namespace {

struct SceneParams {
  std::uint64_t seed;
  int bodies;
  bool lattice;       // positions, sizes and queries on a grid of quarter metres
  bool pile = false;  // a rained pile of circles, mostly asleep, instead
};

class QueryBruteForce : public ::testing::TestWithParam<SceneParams> {
 protected:
  double coordinate(double lo, double hi) {
    const double v = rng_.uniform(lo, hi);
    return GetParam().lattice ? std::round(v * 4.0) / 4.0 : v;
  }
  double size(double lo, double hi) { return std::max(coordinate(lo, hi), 0.25); }
  bool chance(double p) { return rng_.uniform(0.0, 1.0) < p; }
  Vec2 point() {
    if (GetParam().pile) return {coordinate(-12.0, 12.0), coordinate(-1.0, 12.0)};
    return {coordinate(-40.0, 40.0), coordinate(-40.0, 40.0)};
  }

  Filter random_filter() {
    Filter f;
    f.category_bits = 1u << static_cast<int>(rng_.uniform(0.0, 4.0));
    f.mask_bits = static_cast<std::uint32_t>(rng_.uniform(0.0, 16.0));
    f.group = static_cast<std::int32_t>(rng_.uniform(-2.0, 3.0));
    return f;
  }

  BodyDef random_body() {
    BodyDef def;
    def.shape = chance(0.5) ? Shape::Circle : Shape::Box;
    const double roll = rng_.uniform(0.0, 1.0);
    def.motion = roll < 0.3 ? Motion::Static : roll < 0.85 ? Motion::Dynamic : Motion::Kinematic;
    def.position = point();
    def.radius = size(0.1, 1.5);
    def.half_extents = {size(0.1, 1.5), size(0.1, 1.5)};
    if (def.motion == Motion::Static && chance(0.05)) {  // a floor or a wall
      def.shape = Shape::Box;
      def.half_extents = chance(0.5) ? Vec2{30.0, 0.5} : Vec2{0.5, 20.0};
    }
    if (def.motion == Motion::Kinematic)
      def.velocity = {coordinate(-3.0, 3.0), coordinate(-3.0, 3.0)};
    def.is_sensor = chance(0.1);
    if (chance(0.3)) def.filter = random_filter();
    return def;
  }

  QueryFilter random_query_filter() {
    QueryFilter q;
    if (chance(0.5)) q.filter = random_filter();
    q.include_sensors = chance(0.5);
    return q;
  }

  Vec2 translation() {
    if (chance(0.05)) return {};
    const double reach = chance(0.3) ? 100.0 : 12.0;
    return {coordinate(-reach, reach), coordinate(-reach, reach)};
  }

  void build() {
    WorldSettings settings;
    if (GetParam().pile) {
      const scenes::SceneSpec scene =
          scenes::rained_circles_scene({20.0, GetParam().bodies, 0.5, 0});
      settings.gravity = scene.gravity;
      world_ = std::make_unique<World>(settings);
      scenes::add_to_world(*world_, scene);
      return;
    }
    world_ = std::make_unique<World>(settings);
    for (int i = 0; i < GetParam().bodies; ++i) add_or_fail(*world_, random_body());
  }

  // ---- The brute force: every body, one by one ----
  bool passes(const BodyState& b, const QueryFilter& q) const {
    if (world_->is_sensor(b.id) && !q.include_sensors) return false;
    return !q.filter || should_collide(*q.filter, *world_->filter(b.id));
  }
  static PlacedShape shape_of(const BodyState& b) {
    return {b.shape, b.position, b.radius, b.half_extents};
  }
  std::vector<CastHit> all_hits(const PlacedShape& caster, Vec2 translation,
                                const QueryFilter& q) const {
    std::vector<CastHit> hits;
    for (const BodyState& b : world_->bodies()) {
      if (!passes(b, q)) continue;
      if (std::optional<CastHit> hit = cast_against(caster, translation, shape_of(b))) {
        hit->body = b.id;
        hits.push_back(*hit);
      }
    }
    std::stable_sort(hits.begin(), hits.end(), [](const CastHit& a, const CastHit& b) {
      return a.fraction < b.fraction;  // bodies() is in id order: ties stay by id
    });
    return hits;
  }
  template <class Overlaps>
  std::vector<BodyId> all_overlapping(const Overlaps& overlaps, const QueryFilter& q) const {
    std::vector<BodyId> out;
    for (const BodyState& b : world_->bodies()) {
      if (passes(b, q) && overlaps(shape_of(b))) out.push_back(b.id);
    }
    return out;
  }

  static void expect_same(const std::optional<CastHit>& got, const std::vector<CastHit>& all) {
    ASSERT_EQ(got.has_value(), !all.empty());
    if (!got) return;
    EXPECT_EQ(got->body, all.front().body);
    EXPECT_EQ(got->fraction, all.front().fraction);
    EXPECT_EQ(got->point, all.front().point);
    EXPECT_EQ(got->normal, all.front().normal);
  }
  static void expect_same(const std::vector<CastHit>& got, const std::vector<CastHit>& all) {
    ASSERT_EQ(got.size(), all.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].body, all[i].body) << i;
      EXPECT_EQ(got[i].fraction, all[i].fraction) << i;
      EXPECT_EQ(got[i].point, all[i].point) << i;
      EXPECT_EQ(got[i].normal, all[i].normal) << i;
    }
  }

  // `rounds` random queries of each kind, each checked; counts what was found.
  void check_queries(int rounds) {
    for (int i = 0; i < rounds && !::testing::Test::HasFailure(); ++i) {
      const QueryFilter q = random_query_filter();
      const Vec2 from = point();
      const Vec2 along = translation();
      const PlacedShape ray{Shape::Circle, from, 0.0, {}};
      const std::vector<CastHit> ray_hits = all_hits(ray, along, q);
      expect_same(world_->cast_ray(from, along, q), ray_hits);
      expect_same(world_->cast_ray_all(from, along, q), ray_hits);
      hits_ += ray_hits.size();
      for (const CastHit& h : ray_hits) {
        if (h.fraction == 0.0) ++inside_;
      }

      const PlacedShape circle{Shape::Circle, from, size(0.0, 2.0), {}};
      expect_same(world_->cast_circle(from, circle.radius, along, q), all_hits(circle, along, q));
      const PlacedShape box{Shape::Box, from, 0.0, {size(0.0, 2.0), size(0.0, 2.0)}};
      const std::vector<CastHit> box_hits = all_hits(box, along, q);
      expect_same(world_->cast_box(from, box.half_extents, along, q), box_hits);
      cast_hits_ += box_hits.empty() ? 0 : 1;

      const Vec2 corner = point();
      const Aabb region{{std::min(from.x, corner.x), std::min(from.y, corner.y)},
                        {std::min(from.x, corner.x) + std::fabs(corner.x - from.x) * 0.2,
                         std::min(from.y, corner.y) + std::fabs(corner.y - from.y) * 0.2}};
      const std::vector<BodyId> in_box =
          all_overlapping([&region](const PlacedShape& b) { return box_overlaps(region, b); }, q);
      EXPECT_EQ(world_->overlap_box(region, q), in_box);
      overlaps_ += in_box.size();
      EXPECT_EQ(world_->overlap_circle(from, circle.radius, q),
                all_overlapping(
                    [&circle](const PlacedShape& b) { return shapes_overlap(circle, b); }, q));
      const PlacedShape dot{Shape::Circle, from, 0.0, {}};
      EXPECT_EQ(
          world_->overlap_point(from, q),
          all_overlapping([&dot](const PlacedShape& b) { return shapes_overlap(dot, b); }, q));
    }
  }

  // Bodies added, removed and moved by hand, then steps.
  void change_the_world() {
    std::vector<BodyState> bodies = world_->bodies();
    for (std::size_t i = 0; i < bodies.size(); i += 7) world_->remove_body(bodies[i].id);
    for (int i = 0; i < GetParam().bodies / 10; ++i) add_or_fail(*world_, random_body());
    bodies = world_->bodies();
    for (std::size_t i = 3; i < bodies.size(); i += 11) world_->set_position(bodies[i].id, point());
  }

  scenes::SplitMix64 rng_{GetParam().seed};
  std::unique_ptr<World> world_;
  std::size_t hits_ = 0;
  std::size_t inside_ = 0;
  std::size_t cast_hits_ = 0;
  std::size_t overlaps_ = 0;
};

TEST_P(QueryBruteForce, EveryQueryFindsWhatTestingEveryBodyFinds) {
  build();
  check_queries(100);  // before any step: the lists not yet made
  for (int i = 0; i < 20; ++i) world_->step(kDt);
  check_queries(150);
  change_the_world();
  check_queries(100);
  for (int i = 0; i < 5; ++i) world_->step(kDt);
  check_queries(100);
  // The queries were not idle: they found bodies, from inside too, and missed some.
  EXPECT_GT(hits_, 100u);
  EXPECT_GT(inside_, 0u);
  EXPECT_GT(cast_hits_, 50u);
  EXPECT_LT(cast_hits_, 450u);
  EXPECT_GT(overlaps_, 50u);
}

// A pile that has gone mostly to sleep: its sleeping bodies filed apart from the awake
// ones; then some woken by hand and by new bodies, stepped, and asked again.
class PileQueries : public QueryBruteForce {};

TEST_P(PileQueries, ASleepingPileAnswersAsEveryBodyDoes) {
  build();
  for (int i = 0; i < 600; ++i) world_->step(kDt);
  const std::size_t awake = world_->awake_body_count();
  ASSERT_LT(awake, world_->dynamic_body_count() / 2) << "the pile did not settle";
  check_queries(150);
  world_->step(kDt);  // the lists as the step left them
  check_queries(100);
  change_the_world();
  check_queries(100);
  for (int i = 0; i < 30; ++i) world_->step(kDt);
  check_queries(100);
  EXPECT_GT(hits_, 100u);
  EXPECT_GT(overlaps_, 50u);
}

INSTANTIATE_TEST_SUITE_P(Scenes, QueryBruteForce,
                         ::testing::Values(SceneParams{1, 200, true}, SceneParams{2, 200, false},
                                           SceneParams{3, 2000, true}, SceneParams{4, 2000, false}),
                         [](const ::testing::TestParamInfo<SceneParams>& scene) {
                           return std::string(scene.param.lattice ? "Lattice" : "Spread") +
                                  std::to_string(scene.param.bodies) + "Seed" +
                                  std::to_string(scene.param.seed);
                         });

INSTANTIATE_TEST_SUITE_P(Piles, PileQueries, ::testing::Values(SceneParams{5, 300, false, true}),
                         [](const ::testing::TestParamInfo<SceneParams>& scene) {
                           return "Pile" + std::to_string(scene.param.bodies);
                         });

}  // namespace
}  // namespace phys::testing
