// UniformGrid::find_pairs on random scenes of N boxes covering 30% of their area,
// against the brute-force reference where that is affordable.
#include <benchmark/benchmark.h>

#include <vector>

#include "physics/broadphase.h"
#include "scenes/scenes.h"

namespace {

constexpr double kDensity = 0.3;

void BM_GridFindPairs(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  const std::vector<phys::Aabb> boxes = scenes::random_boxes(count, kDensity, 0x5EED0020ULL);
  phys::UniformGrid grid;
  std::vector<phys::BodyPair> pairs;
  for (auto _ : state) {
    grid.find_pairs(boxes, pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  state.counters["pairs"] = static_cast<double>(pairs.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * count);
}
BENCHMARK(BM_GridFindPairs)
    ->Arg(1000)
    ->Arg(4000)
    ->Arg(16000)
    ->Arg(64000)
    ->Unit(benchmark::kMicrosecond);

void BM_BruteForceFindPairs(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  const std::vector<phys::Aabb> boxes = scenes::random_boxes(count, kDensity, 0x5EED0020ULL);
  std::vector<phys::BodyPair> pairs;
  for (auto _ : state) {
    phys::find_pairs_brute_force(boxes, pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  state.counters["pairs"] = static_cast<double>(pairs.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * count);
}
BENCHMARK(BM_BruteForceFindPairs)->Arg(1000)->Arg(4000)->Unit(benchmark::kMicrosecond);

}  // namespace
