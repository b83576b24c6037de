// The narrowphase pair tests on 1,024 random pairs per iteration (random so that
// nothing folds into a constant; about half of them touch).
#include <benchmark/benchmark.h>

#include <vector>

#include "physics/formulas.h"
#include "scenes/scenes.h"

namespace {

constexpr std::size_t kPairs = 1024;

struct Inputs {
  std::vector<phys::Vec2> centers_a;
  std::vector<phys::Vec2> centers_b;
  std::vector<phys::Aabb> boxes_a;
  std::vector<phys::Aabb> boxes_b;
};

const Inputs& inputs() {
  static const Inputs data = [] {
    Inputs in;
    scenes::SplitMix64 random(0x5EED0010ULL);
    for (std::size_t i = 0; i < kPairs; ++i) {
      const phys::Vec2 a{random.uniform(0.0, 2.0), random.uniform(0.0, 2.0)};
      const phys::Vec2 b{random.uniform(0.0, 2.0), random.uniform(0.0, 2.0)};
      in.centers_a.push_back(a);
      in.centers_b.push_back(b);
      in.boxes_a.push_back({a - phys::Vec2{0.5, 0.5}, a + phys::Vec2{0.5, 0.5}});
      in.boxes_b.push_back({b - phys::Vec2{0.4, 0.6}, b + phys::Vec2{0.4, 0.6}});
    }
    return in;
  }();
  return data;
}

void BM_CollideCircles(benchmark::State& state) {
  const Inputs& in = inputs();
  for (auto _ : state) {
    for (std::size_t i = 0; i < kPairs; ++i) {
      benchmark::DoNotOptimize(phys::collide_circles(in.centers_a[i], 0.5, in.centers_b[i], 0.5));
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kPairs));
}
BENCHMARK(BM_CollideCircles);

void BM_CollideCircleBox(benchmark::State& state) {
  const Inputs& in = inputs();
  for (auto _ : state) {
    for (std::size_t i = 0; i < kPairs; ++i) {
      benchmark::DoNotOptimize(phys::collide_circle_box(in.centers_a[i], 0.5, in.boxes_b[i]));
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kPairs));
}
BENCHMARK(BM_CollideCircleBox);

void BM_BoxesIntersect(benchmark::State& state) {
  const Inputs& in = inputs();
  for (auto _ : state) {
    for (std::size_t i = 0; i < kPairs; ++i) {
      benchmark::DoNotOptimize(phys::boxes_intersect(in.boxes_a[i], in.boxes_b[i]));
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kPairs));
}
BENCHMARK(BM_BoxesIntersect);

}  // namespace
