// The step-cost benchmark (docs/BENCHMARKS.md): time of World::step for a pile of N
// bodies (circles and boxes alternating) in a container, N = 1,000, 4,000, 16,000,
// showing how the cost grows.
#include <benchmark/benchmark.h>

#include "engine.h"
#include "scenes/scenes.h"

namespace {

constexpr double kDt = 1.0 / 60.0;

// The lattice falls for `presteps` steps first, so that what is timed is a pile
// (the top row of the 16,000 lattice, 90 m up, lands after about 4.3 s).
std::unique_ptr<bench::Engine> make_pile(int count, bool sleeping, int presteps) {
  bench::EngineOptions options;
  options.sleeping = sleeping;
  auto engine = bench::make_engine(bench::EngineKind::Ours, scenes::pile_scene(count), options);
  for (int i = 0; i < presteps; ++i) engine->step(kDt);
  return engine;
}

// Sleeping off: every body is stepped every time (the cost of a pile in motion).
void BM_StepPileAwake(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  auto engine = make_pile(count, false, 300);
  for (auto _ : state) engine->step(kDt);
  state.counters["bodies"] = count;
  state.counters["us_per_body"] =
      benchmark::Counter(static_cast<double>(count), benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
  state.counters["awake"] = static_cast<double>(engine->awake_count());
}
BENCHMARK(BM_StepPileAwake)->Arg(1000)->Arg(4000)->Arg(16000)->Unit(benchmark::kMillisecond);

// Sleeping on (the server's default), after the pile has had 20 s to settle.
void BM_StepPileSettled(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  auto engine = make_pile(count, true, 1200);
  for (auto _ : state) engine->step(kDt);
  state.counters["bodies"] = count;
  state.counters["awake"] = static_cast<double>(engine->awake_count());
}
BENCHMARK(BM_StepPileSettled)->Arg(1000)->Arg(4000)->Arg(16000)->Unit(benchmark::kMillisecond);

}  // namespace
