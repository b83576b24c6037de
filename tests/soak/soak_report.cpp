// The report's figures, derived from the run's record, printed and written as CSV.
#include "soak_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

namespace soak {
namespace {

// The tick-time quantile from the server's histogram: the upper bound of the bucket
// it falls in (infinity for the overflow bucket).
double histogram_quantile(const server::ServerStats& stats, double q) {
  std::uint64_t total = 0;
  for (const std::uint64_t count : stats.tick_seconds_buckets) total += count;
  if (total == 0) return 0.0;
  const auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(total)));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < stats.tick_seconds_buckets.size(); ++i) {
    seen += stats.tick_seconds_buckets[i];
    if (seen >= rank) {
      return i < server::kTickSecondsBounds.size() ? server::kTickSecondsBounds[i]
                                                   : std::numeric_limits<double>::infinity();
    }
  }
  return std::numeric_limits<double>::infinity();
}

const char* encoding_name(client::Encoding encoding) {
  switch (encoding) {
    case client::Encoding::Full:
      return "full";
    case client::Encoding::Exact:
      return "exact";
    case client::Encoding::Inputs:
      return "inputs";
    case client::Encoding::Predicted:
      break;
  }
  return "predicted";
}

// Session ends the tool caused or expects, each up to the number it caused: its own
// leaves (a Bye; or Disconnected: a close with snapshots still unread makes the
// kernel send a reset, which the server may see before it reads the Bye),
// joins refused for want of room for another body, and the server's stop. Every
// other session end, and any beyond those counts, is a drop the tool did not ask for.
std::uint64_t unexplained_ends(const server::ServerStats& stats, const Tally& tally,
                               std::uint64_t joined_at_stop) {
  const auto count = [&](server::DropReason reason) -> std::uint64_t {
    const auto it = stats.dropped.find(reason);
    return it == stats.dropped.end() ? 0 : it->second;
  };
  const auto excess = [](std::uint64_t seen, std::uint64_t allowed) {
    return seen > allowed ? seen - allowed : 0;
  };
  using R = server::DropReason;
  std::uint64_t other = 0;
  for (const auto& [reason, n] : stats.dropped) {
    if (reason != R::ClientBye && reason != R::Disconnected && reason != R::NoSpawn &&
        reason != R::ShuttingDown) {
      other += n;
    }
  }
  return other + excess(count(R::ClientBye) + count(R::Disconnected), tally.leaves) +
         excess(count(R::NoSpawn), tally.join_refused_no_spawn) +
         excess(count(R::ShuttingDown), joined_at_stop);
}

// The figures the report prints and the CSV line holds.
struct Figures {
  std::uint64_t desyncs = 0;
  std::uint64_t unexplained = 0;
  std::string drops;                // "reason count, ..." over every session end
  std::int64_t growth = 0;          // resident bytes, end against warm-up
  std::int64_t trimmed_growth = 0;  // the same after malloc_trim
  std::int64_t peak_growth = 0;     // the largest sample after warm-up against warm-up
  double budget_ms = 0.0;
  double p99_ms = 0.0;
  double mean_ms = 0.0;
  double mean_after_warm_ms = 0.0;
  const char* mode = "";
};

Figures figures(const Options& options, const RunRecord& run, const Tally& tally,
                const ReplayCheck& replayed) {
  const server::ServerStats& stats = run.at_end;
  Figures f;
  f.unexplained = tally.lost_sessions + tally.join_failures +
                  unexplained_ends(stats, tally, run.joined_at_stop);
  for (const auto& [reason, count] : stats.dropped) {
    f.drops +=
        fmt::format("{}{} {}", f.drops.empty() ? "" : ", ", server::to_string(reason), count);
  }
  f.desyncs = replayed.client_mismatches + replayed.recorded_mismatches +
              tally.cross_client_conflicts + replayed.client_unreplayed;

  std::uint64_t rss_max_after = 0;
  for (const auto& [t, bytes] : run.rss) {
    if (t >= options.warmup) rss_max_after = std::max(rss_max_after, bytes);
  }
  const auto at_warm = static_cast<std::int64_t>(run.rss_at_warm);
  f.growth = static_cast<std::int64_t>(run.rss_end) - at_warm;
  f.trimmed_growth = static_cast<std::int64_t>(run.rss_trimmed) - at_warm;
  f.peak_growth = static_cast<std::int64_t>(rss_max_after) - at_warm;
  f.budget_ms = 1000.0 / run.tick_rate;
  f.p99_ms = 1000.0 * histogram_quantile(stats, 0.99);
  f.mean_ms = stats.ticks_stepped > 0
                  ? 1000.0 * stats.total_tick_seconds / static_cast<double>(stats.ticks_stepped)
                  : 0.0;
  const double warm_ticks = static_cast<double>(stats.ticks_stepped - run.at_warm.ticks_stepped);
  f.mean_after_warm_ms =
      warm_ticks > 0
          ? 1000.0 * (stats.total_tick_seconds - run.at_warm.total_tick_seconds) / warm_ticks
          : 0.0;
  f.mode = options.lockstep ? "lockstep" : "fixed-rate";
  return f;
}

// The resident set at each tenth of the time after warm-up, in MB: a leak climbs
// steadily, an allocator settling steps up and stays.
std::string rss_trajectory(const Options& options, const RunRecord& run) {
  std::string trajectory;
  for (int tenth = 1; tenth <= 10; ++tenth) {
    const double at = options.warmup + (options.duration - options.warmup) * tenth / 10.0;
    std::uint64_t bytes = run.rss_end;
    for (const auto& [t, sampled] : run.rss) {
      if (t <= at) bytes = sampled;
    }
    trajectory += fmt::format("{}{:.1f}", tenth == 1 ? "" : " ", static_cast<double>(bytes) / 1e6);
  }
  return trajectory;
}

void print_report(const Options& options, const RunRecord& run, const Tally& tally,
                  const ReplayCheck& replayed, const Figures& f) {
  const server::ServerStats& stats = run.at_end;
  fmt::print("physics-soak: {} on {}, {} slots, {} encoding, {:.0f} s, seed {}\n", f.mode,
             run.scene_name, options.clients, encoding_name(options.encoding), options.duration,
             options.seed);
  fmt::print("  ticks stepped {}, replayed {}; client hashes {} over {} ticks, all compared: {}\n",
             stats.ticks_stepped, replayed.ticks, tally.hash_samples, tally.hashes.size(),
             replayed.client_compared);
  fmt::print(
      "  desyncs {} (client vs replay {}, recording vs replay {}, between clients {}, beyond the "
      "replay {}); client view-hash resyncs {}\n",
      f.desyncs, replayed.client_mismatches, replayed.recorded_mismatches,
      tally.cross_client_conflicts, replayed.client_unreplayed, tally.view_desyncs);
  fmt::print(
      "  script: joins {}, leaves {}, read stalls {}; joins refused for no spawn room {}, "
      "other join failures {}, sessions lost {}\n",
      tally.joins, tally.leaves, tally.stalls, tally.join_refused_no_spawn, tally.join_failures,
      tally.lost_sessions);
  fmt::print(
      "  sessions ended by reason: {}; unexplained {} (a Bye or a reset for each of the tool's "
      "leaves, a refusal for each join without room, a shutdown for each client at the stop)\n",
      f.drops.empty() ? "none" : f.drops, f.unexplained);
  fmt::print(
      "  resident memory (whole process): {:.1f} MB at warm-up ({:.0f} s), {:.1f} MB at the end: "
      "growth {} bytes (peak after warm-up {} bytes)\n",
      static_cast<double>(run.rss_at_warm) / 1e6, options.warmup,
      static_cast<double>(run.rss_end) / 1e6, f.growth, f.peak_growth);
  fmt::print(
      "  resident memory at each tenth after warm-up, MB: {}; after malloc_trim: growth {} bytes "
      "(the tool's own record of {} ticks' hashes included)\n",
      rss_trajectory(options, run), f.trimmed_growth, tally.hashes.size());
  fmt::print(
      "  server structures at the end: input buffers {} bytes (peak {}), views {}, peak queued "
      "snapshots {}, open connections {}\n",
      run.before_stop.input_buffer_bytes, run.peak_input_bytes, run.before_stop.views,
      stats.peak_queued_snapshots, run.before_stop.open_connections);
  fmt::print(
      "  tick time: p99 <= {:.3f} ms (histogram bound), mean {:.3f} ms ({:.3f} after warm-up), "
      "max {:.3f} ms; budget {:.3f} ms: p99 {}; overruns {}, dropped steps {}, skipped "
      "snapshots {}, lockstep timeouts {}\n",
      f.p99_ms, f.mean_ms, f.mean_after_warm_ms, 1000.0 * stats.max_tick_seconds, f.budget_ms,
      f.p99_ms <= f.budget_ms ? "within" : "OVER", stats.tick_overruns, stats.dropped_steps,
      stats.skipped_snapshots, stats.lockstep_timeouts);
}

// Appends one line to options.csv_path, a header first when the file is new or
// empty; false when it cannot be opened.
bool append_csv(const Options& options, const RunRecord& run, const Tally& tally,
                const Figures& f) {
  const server::ServerStats& stats = run.at_end;
  const bool fresh = !std::filesystem::exists(options.csv_path) ||
                     std::filesystem::file_size(options.csv_path) == 0;
  std::FILE* csv = std::fopen(options.csv_path.c_str(), "a");
  if (csv == nullptr) return false;
  if (fresh) {
    fmt::print(csv,
               "scene,mode,slots,seconds,seed,ticks,client_hashes,desyncs,joins,leaves,stalls,"
               "no_spawn_refusals,unexplained_drops,rss_warm_bytes,rss_growth_bytes,"
               "rss_peak_growth_bytes,rss_trimmed_growth_bytes,input_buffer_bytes_peak,tick_ms_"
               "mean,tick_ms_p99_bound,"
               "tick_ms_max,budget_ms,overruns,dropped_steps,skipped_snapshots\n");
  }
  fmt::print(csv,
             "{},{},{},{:.0f},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.4f},{:.4f},{:.4f},"
             "{:.4f},{},{},{}\n",
             run.scene_name, f.mode, options.clients, options.duration, options.seed,
             stats.ticks_stepped, tally.hash_samples, f.desyncs, tally.joins, tally.leaves,
             tally.stalls, tally.join_refused_no_spawn, f.unexplained, run.rss_at_warm, f.growth,
             f.peak_growth, f.trimmed_growth, run.peak_input_bytes, f.mean_ms, f.p99_ms,
             1000.0 * stats.max_tick_seconds, f.budget_ms, stats.tick_overruns, stats.dropped_steps,
             stats.skipped_snapshots);
  std::fclose(csv);
  return true;
}

}  // namespace

int report(const Options& options, const RunRecord& run, const Tally& tally,
           const ReplayCheck& replayed) {
  const Figures f = figures(options, run, tally, replayed);
  print_report(options, run, tally, replayed, f);
  if (!options.csv_path.empty() && !append_csv(options, run, tally, f)) {
    fmt::print(stderr, "physics-soak: cannot write {}\n", options.csv_path);
    return 2;
  }
  const bool ok = f.desyncs == 0 && f.unexplained == 0 && replayed.client_compared > 0;
  fmt::print("  result: {}\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}

}  // namespace soak
