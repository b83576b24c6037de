// What one rollback of a predicting client costs (docs/BENCHMARKS.md, "The
// predicting client"): the confirmed state restored (World::restore) and 8 ticks
// stepped again, the depth of a rollback at a 100 ms round trip and 60 Hz (about
// 6 ticks in flight and a margin). A frame of 16.7 ms has room for it when it takes
// under half of one, 8.35 ms. On a rain of N circles 1 s into its fall (every body
// awake, many new contacts) and on N circles rained into a pile for 5 s.
#include <benchmark/benchmark.h>

#include "physics/world.h"
#include "scenes/scenes.h"
#include "stepped_world.h"

namespace {

using microbench::kDt;
using microbench::stepped_world;

constexpr int kRollbackTicks = 8;

// Arg 0: 0 the rain, 1 the rained pile; arg 1: circles.
phys::World rollback_scene(const benchmark::State& state) {
  const int count = static_cast<int>(state.range(1));
  if (state.range(0) == 0) return stepped_world(scenes::rain_scene(count, 1, 0, 0), 60);
  return stepped_world(scenes::rained_circles_scene(scenes::circle_pile(count, 0.5)), 300);
}

void BM_Rollback8(benchmark::State& state) {
  phys::World world = rollback_scene(state);
  const phys::SavedWorld confirmed = world.save();
  for (auto _ : state) {
    world.restore(confirmed);
    for (int i = 0; i < kRollbackTicks; ++i) world.step(kDt);
  }
  state.counters["bodies"] = static_cast<double>(world.body_count());
  state.counters["awake"] = static_cast<double>(world.awake_body_count());
}

void rollback_args(benchmark::internal::Benchmark* b) {
  for (const int kind : {0, 1}) {
    for (const int count : {1000, 2000, 4000, 8000, 16000}) b->Args({kind, count});
  }
  b->ArgNames({"pile", "circles"});
  b->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_Rollback8)->Apply(rollback_args);

}  // namespace
