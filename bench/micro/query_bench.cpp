// What the world's queries cost (physics/query.h; docs/BENCHMARKS.md, "Queries"): each
// query, one call per iteration, cycling through 256 fixed random queries over a pile
// of 1,000 or 16,000 circles rained for 5 s (bench/run-report.sh --only query-cost).
// Beside them: the first query after the world changed (the moving bodies filed in
// their grid again), and a box test against every body, the loop a query replaces.
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "physics/query.h"
#include "physics/world.h"
#include "scenes/random.h"
#include "scenes/scenes.h"
#include "stepped_world.h"

namespace {

constexpr int kQueries = 256;
constexpr double kReach = 10.0;  // m: a cast's length, a sweeper's or a sight line's

struct Pile {
  std::unique_ptr<phys::World> world;
  std::vector<phys::Vec2> points;  // where each query starts, among the circles
  std::vector<phys::Vec2> directions;
  phys::BodyId some_body;
};

// The rained pile of `count` circles, built once per count for every benchmark.
const Pile& pile(int count) {
  static std::map<int, Pile> piles;
  auto found = piles.find(count);
  if (found != piles.end()) return found->second;
  Pile p;
  p.world = std::make_unique<phys::World>(microbench::stepped_world(
      scenes::rained_circles_scene(scenes::circle_pile(count, 0.5)), 300));
  phys::Vec2 lo{HUGE_VAL, HUGE_VAL};
  phys::Vec2 hi{-HUGE_VAL, -HUGE_VAL};
  for (const phys::BodyState& b : p.world->bodies()) {
    if (b.motion != phys::Motion::Dynamic) continue;
    lo = {std::fmin(lo.x, b.position.x), std::fmin(lo.y, b.position.y)};
    hi = {std::fmax(hi.x, b.position.x), std::fmax(hi.y, b.position.y)};
    p.some_body = b.id;
  }
  scenes::SplitMix64 rng(0x9E37u + static_cast<std::uint64_t>(count));
  for (int i = 0; i < kQueries; ++i) {
    p.points.push_back({rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y)});
    const double angle = rng.uniform(0.0, 6.283185307179586);
    p.directions.push_back({kReach * std::cos(angle), kReach * std::sin(angle)});
  }
  return piles.emplace(count, std::move(p)).first->second;
}

// Runs `query(world, point, direction)` once an iteration, through the fixed list;
// counts what it found on average.
template <class Query>
void run_queries(benchmark::State& state, const Query& query) {
  const Pile& p = pile(static_cast<int>(state.range(0)));
  std::size_t found = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    found += query(*p.world, p.points[i], p.directions[i]);
    i = (i + 1) % kQueries;
  }
  state.counters["found_per_query"] =
      static_cast<double>(found) / static_cast<double>(state.iterations());
  state.counters["bodies"] = static_cast<double>(p.world->body_count());
}

void BM_QueryCastRay(benchmark::State& state) {
  run_queries(state, [](const phys::World& w, phys::Vec2 at, phys::Vec2 along) {
    return static_cast<std::size_t>(w.cast_ray(at, along).has_value());
  });
}
void BM_QueryCastRayAll(benchmark::State& state) {
  run_queries(state, [](const phys::World& w, phys::Vec2 at, phys::Vec2 along) {
    return w.cast_ray_all(at, along).size();
  });
}
// Across the whole pile, left wall to right wall, at the query's height.
void BM_QueryCastRayAcross(benchmark::State& state) {
  run_queries(state, [](const phys::World& w, phys::Vec2 at, phys::Vec2) {
    return w.cast_ray_all({-60.0, at.y}, {120.0, 0.0}).size();
  });
}
void BM_QueryOverlapBox(benchmark::State& state) {
  run_queries(state, [](const phys::World& w, phys::Vec2 at, phys::Vec2) {
    return w.overlap_box({at - phys::Vec2{1.0, 1.0}, at + phys::Vec2{1.0, 1.0}}).size();
  });
}
void BM_QueryOverlapCircle(benchmark::State& state) {
  run_queries(state, [](const phys::World& w, phys::Vec2 at, phys::Vec2) {
    return w.overlap_circle(at, 1.0).size();
  });
}
void BM_QueryOverlapPoint(benchmark::State& state) {
  run_queries(state, [](const phys::World& w, phys::Vec2 at, phys::Vec2) {
    return w.overlap_point(at).size();
  });
}
void BM_QueryCastCircle(benchmark::State& state) {
  run_queries(state, [](const phys::World& w, phys::Vec2 at, phys::Vec2 along) {
    return static_cast<std::size_t>(w.cast_circle(at, 0.5, along).has_value());
  });
}
void BM_QueryCastBox(benchmark::State& state) {
  run_queries(state, [](const phys::World& w, phys::Vec2 at, phys::Vec2 along) {
    return static_cast<std::size_t>(w.cast_box(at, {0.5, 0.5}, along).has_value());
  });
}

// A body moved (to where it is) before each query: the query files the moving bodies
// in their grid again first, as the first query after a step does.
void BM_QueryFirstAfterChange(benchmark::State& state) {
  const Pile& p = pile(static_cast<int>(state.range(0)));
  const phys::Vec2 where = p.world->body(p.some_body)->position;
  std::size_t i = 0;
  for (auto _ : state) {
    p.world->set_position(p.some_body, where);
    benchmark::DoNotOptimize(p.world->overlap_point(p.points[i]));
    i = (i + 1) % kQueries;
  }
  state.counters["bodies"] = static_cast<double>(p.world->body_count());
}

// The loop over every body that overlap_box replaces: each body's box against the
// query's, through for_each_body.
void BM_QueryBoxByHand(benchmark::State& state) {
  run_queries(state, [](const phys::World& w, phys::Vec2 at, phys::Vec2) {
    const phys::Aabb box{at - phys::Vec2{1.0, 1.0}, at + phys::Vec2{1.0, 1.0}};
    std::size_t found = 0;
    w.for_each_body([&](const phys::BodyState& b) {
      const phys::PlacedShape shape{b.shape, b.position, b.radius, b.half_extents};
      found += phys::box_overlaps(box, shape) ? 1 : 0;
    });
    return found;
  });
}

void query_args(benchmark::internal::Benchmark* b) {
  b->Arg(1000)->Arg(16000)->ArgName("circles")->Unit(benchmark::kMicrosecond);
}

BENCHMARK(BM_QueryCastRay)->Apply(query_args);
BENCHMARK(BM_QueryCastRayAll)->Apply(query_args);
BENCHMARK(BM_QueryCastRayAcross)->Apply(query_args);
BENCHMARK(BM_QueryOverlapBox)->Apply(query_args);
BENCHMARK(BM_QueryOverlapCircle)->Apply(query_args);
BENCHMARK(BM_QueryOverlapPoint)->Apply(query_args);
BENCHMARK(BM_QueryCastCircle)->Apply(query_args);
BENCHMARK(BM_QueryCastBox)->Apply(query_args);
BENCHMARK(BM_QueryFirstAfterChange)->Apply(query_args);
BENCHMARK(BM_QueryBoxByHand)->Apply(query_args);

}  // namespace
