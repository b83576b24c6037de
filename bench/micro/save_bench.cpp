// The cost of a world's saved state (docs/BENCHMARKS.md, "The world's state"): what a
// predicting client pays to keep a state per tick (World::save_into), to roll back
// (World::restore) and to be sent the world (World::to_bytes, World::from_bytes),
// on a falling rain (many contacts and warm starts) and on a resting pile.
#include <benchmark/benchmark.h>

#include <span>

#include "physics/world.h"
#include "scenes/scenes.h"
#include "stepped_world.h"

namespace {

using microbench::kDt;
using microbench::stepped_world;

// Arg: 0 the rain of N circles 1 s into its fall, 1 the pile of N after 5 s.
phys::World scene_for(const benchmark::State& state) {
  const int count = static_cast<int>(state.range(1));
  return state.range(0) == 0 ? stepped_world(scenes::rain_scene(count, 1, 0, 0), 60)
                             : stepped_world(scenes::pile_scene(count), 300);
}

void per_body(benchmark::State& state, const phys::World& world, double bytes) {
  const double bodies = static_cast<double>(world.body_count());
  state.counters["bodies"] = bodies;
  state.counters["bytes_per_body"] = bytes / bodies;
  state.counters["us_per_body"] = benchmark::Counter(
      bodies, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_SaveInto(benchmark::State& state) {
  phys::World world = scene_for(state);
  phys::SavedWorld slot;
  world.save_into(slot);  // its arrays grown once, as a client's ring holds them
  for (auto _ : state) world.save_into(slot);
  per_body(state, world, static_cast<double>(slot.bytes()));
}

void BM_Restore(benchmark::State& state) {
  phys::World world = scene_for(state);
  const phys::SavedWorld saved = world.save();
  for (auto _ : state) world.restore(saved);
  per_body(state, world, static_cast<double>(saved.bytes()));
}

void BM_ToBytes(benchmark::State& state) {
  const phys::World world = scene_for(state);
  std::size_t size = 0;
  for (auto _ : state) {
    const std::vector<std::uint8_t> bytes = world.to_bytes();
    size = bytes.size();
    benchmark::DoNotOptimize(bytes.data());
  }
  per_body(state, world, static_cast<double>(size));
}

void BM_FromBytes(benchmark::State& state) {
  const phys::World world = scene_for(state);
  const std::vector<std::uint8_t> bytes = world.to_bytes();
  for (auto _ : state) {
    std::optional<phys::World> loaded = phys::World::from_bytes(bytes);
    benchmark::DoNotOptimize(loaded);
  }
  per_body(state, world, static_cast<double>(bytes.size()));
}

// One step, for scale: a rollback of N ticks is a restore and N of these.
void BM_StepForScale(benchmark::State& state) {
  phys::World world = scene_for(state);
  const phys::SavedWorld saved = world.save();
  for (auto _ : state) {
    state.PauseTiming();
    world.restore(saved);
    state.ResumeTiming();
    world.step(kDt);
  }
  per_body(state, world, 0.0);
}

void scenes_args(benchmark::internal::Benchmark* b) {
  for (const int kind : {0, 1}) {
    for (const int count : {1000, 4000}) b->Args({kind, count});
  }
  b->Unit(benchmark::kMicrosecond);
}

BENCHMARK(BM_SaveInto)->Apply(scenes_args);
BENCHMARK(BM_Restore)->Apply(scenes_args);
BENCHMARK(BM_ToBytes)->Apply(scenes_args);
BENCHMARK(BM_FromBytes)->Apply(scenes_args);
BENCHMARK(BM_StepForScale)->Apply(scenes_args);

}  // namespace
