// physics-microbench's main: Google Benchmark's, but a flag it does not know exits 2,
// as with every executable of the product (benchmark_main exits 1).
#include <benchmark/benchmark.h>

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
