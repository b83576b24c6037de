#pragma once
// physics-soak's report: the figures of one run on stdout (desyncs, session ends by
// reason, resident memory, server structure sizes, tick time against the budget),
// optionally one CSV line, and the verdict.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "client_fleet.h"
#include "replay_check.h"
#include "server/server.h"
#include "soak_options.h"

namespace soak {

// What the driver measured over one run.
struct RunRecord {
  std::string scene_name;
  double tick_rate = 0.0;
  server::ServerStats at_warm;      // at the first sample after warm-up
  server::ServerStats before_stop;  // just before the server was told to stop
  server::ServerStats at_end;       // after the server stopped
  std::uint64_t joined_at_stop = 0;
  std::vector<std::pair<double, std::uint64_t>> rss;  // (seconds since start, bytes)
  std::uint64_t rss_at_warm = 0;
  std::uint64_t rss_end = 0;
  std::uint64_t rss_trimmed = 0;  // at the end, after malloc_trim
  std::size_t peak_input_bytes = 0;
};

// Prints the report (and appends the CSV line with --csv). Returns the exit code:
// 0 every check passed, 1 a desync or an unexplained drop, 2 the CSV file cannot be
// written.
int report(const Options& options, const RunRecord& run, const Tally& tally,
           const ReplayCheck& replayed);

}  // namespace soak
