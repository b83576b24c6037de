#include "path_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include "client/load.h"
#include "csv_out.h"
#include "physics_testing/clients.h"
#include "physics_testing/in_process_server.h"
#include "physics_testing/link_conditioner.h"
#include "physics_testing/lockstep_check.h"

namespace netbench {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

struct Path {
  int one_way_ms = 0;
  int jitter_ms = 0;
  int stall_ms = 0;
  int stall_every_ms = 0;
};

// "clock": the client library's defaults (inputs ahead on the client's clock, a
// window grown with the round trip); "after-snapshot": the input for T+1 once the
// snapshot of T arrived and a window of 12 asked for, for comparison.
enum class Behaviour { OnClock, AfterSnapshot };

const char* name(Behaviour b) { return b == Behaviour::OnClock ? "clock" : "after-snapshot"; }

struct Row {
  std::string mode;  // "lockstep" or "fixed"
  int clients = 0;
  Behaviour behaviour = Behaviour::OnClock;
  Path path;
  double seconds = 0.0;
  // Lockstep.
  double ticks_per_second = 0.0;
  double delay_median = 0.0;
  std::uint32_t delay_max = 0;
  std::uint64_t timeouts_steady = 0;
  bool hashes_equal = false;
  std::size_t missing = 0;
  double recovery_ms = 0.0;  // after a stall, until 30 ticks in a row came at the tick rate
  // Fixed rate.
  double snapshots_per_second = 0.0;
  double latency_median_ms = 0.0;
  double latency_p99_ms = 0.0;
  double age_median_ms = 0.0;
  double age_p99_ms = 0.0;
  double kbit_per_second = 0.0;
  std::uint64_t skipped = 0;
  std::string note;
};

physics_testing::PathConfig path_config(const Path& path) {
  physics_testing::PathConfig config = physics_testing::symmetric_path(
      std::chrono::milliseconds(path.one_way_ms), std::chrono::milliseconds(path.jitter_ms));
  config.stalls.duration = std::chrono::milliseconds(path.stall_ms);
  config.stalls.every = std::chrono::milliseconds(path.stall_every_ms);
  return config;
}

client::PacerConfig pacer_for(Behaviour behaviour) {
  client::PacerConfig pacer;
  if (behaviour == Behaviour::AfterSnapshot) pacer.schedule = client::InputSchedule::AfterSnapshot;
  return pacer;
}

client::Vec2 scripted(std::size_t k, std::uint64_t tick) {
  const double angle =
      2.0 * M_PI * (static_cast<double>(tick % 120) / 120.0 + static_cast<double>(k) / 8.0);
  return {4.0 * std::cos(angle), 4.0 * std::sin(angle)};
}

// Ticks a second over the arrivals from index `from` on.
double rate(const std::vector<std::optional<Clock::time_point>>& arrivals, std::size_t from) {
  std::optional<Clock::time_point> first;
  std::optional<Clock::time_point> last;
  std::size_t first_i = 0;
  std::size_t last_i = 0;
  for (std::size_t i = from; i < arrivals.size(); ++i) {
    if (!arrivals[i]) continue;
    if (!first) {
      first = arrivals[i];
      first_i = i;
    }
    last = arrivals[i];
    last_i = i;
  }
  if (!first || last_i == first_i) return 0.0;
  return static_cast<double>(last_i - first_i) /
         std::chrono::duration<double>(*last - *first).count();
}

// After each gap of more than four periods between arrivals (a stall), the time
// until 30 ticks in a row arrive at the tick rate (2% slack); the worst of them.
double worst_recovery_ms(const std::vector<std::optional<Clock::time_point>>& arrivals,
                         double period_s) {
  std::vector<Clock::time_point> at;
  for (const auto& a : arrivals)
    if (a) at.push_back(*a);
  const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
  double worst = 0.0;
  for (std::size_t i = 1; i < at.size(); ++i) {
    if (seconds(at[i] - at[i - 1]) <= 4.0 * period_s) continue;
    std::optional<double> recovered;
    for (std::size_t j = i; j + 30 < at.size(); ++j) {
      if (seconds(at[j + 30] - at[j]) <= 30.0 * period_s * 1.02) {
        recovered = seconds(at[j] - at[i]) * 1000.0;
        break;
      }
    }
    worst = std::max(worst, recovered.value_or(-1.0e9));
  }
  return worst;
}

Row run_lockstep(const PathGridOptions& options, int clients, const Path& path,
                 Behaviour behaviour) {
  Row row;
  row.mode = "lockstep";
  row.clients = clients;
  row.behaviour = behaviour;
  row.path = path;
  row.seconds = options.seconds * (path.stall_ms > 0 ? 2.0 : 1.0);
  server::ServerConfig config = physics_testing::test_server_config(true);
  config.tick_rate = options.tick_rate;
  config.lockstep_pace = server::ServerConfig::Pace::Realtime;
  config.lockstep_players = clients;
  physics_testing::InProcessServer server(options.lockstep_scene, config);
  physics_testing::LinkConditioner link(
      physics_testing::relay_to(server.port(), path_config(path)));
  physics_testing::Endpoint endpoint;
  endpoint.port = link.port();
  client::ClientConfig base = endpoint.exact_client_config("netbench");
  if (behaviour == Behaviour::AfterSnapshot) base.view.window = 12;
  auto joined = physics_testing::connect_clients(base, static_cast<std::size_t>(clients), 20s);
  if (!joined) {
    row.note = joined.message();
    return row;
  }
  const double period = 1.0 / options.tick_rate;
  // The first second settles; the rest is measured. After each snapshot, a tick costs a
  // round trip.
  const double tick_cost = behaviour == Behaviour::OnClock
                               ? period
                               : std::max(period, 2.0 * path.one_way_ms / 1000.0 + period);
  const auto settle = static_cast<std::uint64_t>(std::ceil(1.0 / tick_cost));
  const std::uint64_t ticks = settle + static_cast<std::uint64_t>(row.seconds / tick_cost);
  physics_testing::PacedLockstepOptions run_options;
  run_options.ticks = ticks;
  run_options.pacer = pacer_for(behaviour);
  run_options.timeout =
      std::chrono::milliseconds(static_cast<long>((row.seconds * 3.0 + 30.0) * 1000.0));
  const std::uint64_t start = (*joined)[0]->welcome().current_tick;
  std::atomic<std::uint64_t> timeouts_at_settle{0};
  run_options.on_snapshot = [&](std::size_t k, std::uint64_t tick) {
    if (k == 0 && tick == start + settle) timeouts_at_settle = server.stats().lockstep_timeouts;
  };
  auto run =
      physics_testing::run_paced_lockstep(options.lockstep_scene, *joined, scripted, run_options);
  row.timeouts_steady = server.stats().lockstep_timeouts - timeouts_at_settle.load();
  row.hashes_equal = static_cast<bool>(run);
  if (!run) {
    row.note = run.message();
    return row;
  }
  std::vector<double> delays;
  double rate_sum = 0.0;
  for (const auto& c : run->clients) {
    rate_sum += rate(c.arrivals, settle);
    for (std::size_t i = settle; i < c.delays.size(); ++i) delays.push_back(c.delays[i]);
    row.delay_max = std::max(row.delay_max, c.final_delay);
    row.missing += c.missing;
    if (path.stall_ms > 0)
      row.recovery_ms = std::max(row.recovery_ms, worst_recovery_ms(c.arrivals, period));
  }
  row.ticks_per_second = rate_sum / static_cast<double>(run->clients.size());
  row.delay_median = client::quantile(delays, 0.5);
  return row;
}

Row run_fixed(const PathGridOptions& options, const Path& path, Behaviour behaviour) {
  Row row;
  row.mode = "fixed";
  row.clients = 1;
  row.behaviour = behaviour;
  row.path = path;
  row.seconds = options.seconds * (path.stall_ms > 0 ? 2.0 : 1.0);
  server::ServerConfig config = physics_testing::test_server_config(false);
  config.tick_rate = options.tick_rate;
  physics_testing::InProcessServer server(options.fixed_scene, config);
  physics_testing::LinkConditioner link(
      physics_testing::relay_to(server.port(), path_config(path)));
  client::LoadConfig load;
  load.client.port = link.port();
  load.client.name = "netbench";
  if (behaviour == Behaviour::AfterSnapshot) load.client.view.window = 12;
  load.pacer = pacer_for(behaviour);
  load.bots = 1;
  load.settle = 1s;
  load.duration = std::chrono::milliseconds(static_cast<long>(row.seconds * 1000.0));
  const std::uint64_t skipped_before = server.stats().skipped_snapshots;
  const client::LoadReport report = client::run_load(load);
  row.skipped = server.stats().skipped_snapshots - skipped_before;
  row.snapshots_per_second = report.snapshots_per_second_mean;
  row.latency_median_ms = report.latency_median_ms;
  row.latency_p99_ms = report.latency_p99_ms;
  row.age_median_ms = report.snapshot_age_median_ms;
  row.age_p99_ms = report.snapshot_age_p99_ms;
  row.kbit_per_second = 8.0 * report.bytes_per_second_mean / 1000.0;
  row.delay_median = report.input_delay_median;
  row.delay_max = report.input_delay_max;
  if (!report.failures.empty()) row.note = report.failures.front();
  return row;
}

void print_row(const Row& r, double tick_rate, std::FILE* csv) {
  const double period_ms = 1000.0 / tick_rate;
  // The bound on the delay: half the round trip plus the jitter plus a tick.
  const double bound = (r.path.one_way_ms + r.path.jitter_ms) / period_ms + 1.0;
  if (r.mode == "lockstep") {
    fmt::print(
        "| lockstep {} | {} | {} | {} | {} | {:.1f} | {} | {} | {} | {} | {} |\n", r.clients,
        name(r.behaviour), r.path.one_way_ms, r.path.jitter_ms,
        r.path.stall_ms > 0 ? fmt::format("{}/{}", r.path.stall_ms, r.path.stall_every_ms) : "-",
        r.ticks_per_second,
        // After each snapshot, the input for T+1 goes on the snapshot of T: no delay is chosen.
        r.behaviour == Behaviour::OnClock
            ? fmt::format("{:.1f} (max {}; bound {:.1f})", r.delay_median, r.delay_max, bound)
            : std::string("-"),
        r.timeouts_steady, r.hashes_equal ? "yes" : "NO", r.missing,
        r.path.stall_ms > 0 ? fmt::format("{:.0f}", r.recovery_ms) : "-");
  } else {
    fmt::print(
        "| {} | {} | {} | {} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {} | {} |\n",
        name(r.behaviour), r.path.one_way_ms, r.path.jitter_ms,
        r.path.stall_ms > 0 ? fmt::format("{}/{}", r.path.stall_ms, r.path.stall_every_ms) : "-",
        r.snapshots_per_second, r.latency_median_ms, r.latency_p99_ms, r.age_median_ms,
        r.age_p99_ms, r.kbit_per_second, r.skipped,
        r.behaviour == Behaviour::OnClock ? fmt::format("{:.1f}", r.delay_median)
                                          : std::string("-"));
  }
  if (!r.note.empty()) fmt::print(stderr, "  note: {}\n", r.note);
  if (csv != nullptr) {
    fmt::print(csv,
               "{},{},{},{},{},{},{},{:.1f},{:.2f},{:.1f},{},{:.2f},{},{},{},{:.0f},{:.2f},{:.2f},"
               "{:.2f},{:.2f},{:.2f},{:.2f},{}\n",
               r.mode, r.clients, name(r.behaviour), r.path.one_way_ms, r.path.jitter_ms,
               r.path.stall_ms, r.path.stall_every_ms, r.seconds, r.ticks_per_second,
               r.delay_median, r.delay_max, bound, r.timeouts_steady, r.hashes_equal ? 1 : 0,
               r.missing, r.recovery_ms, r.snapshots_per_second, r.latency_median_ms,
               r.latency_p99_ms, r.age_median_ms, r.age_p99_ms, r.kbit_per_second, r.skipped);
    std::fflush(csv);
  }
  std::fflush(stdout);
}

}  // namespace

int run_path_grid(const PathGridOptions& options) {
  const CsvOut out =
      open_csv(options.csv_path,
               "mode,clients,behaviour,one_way_ms,jitter_ms,stall_ms,stall_every_ms,seconds,"
               "ticks_per_s,input_delay_median,input_delay_max,input_delay_bound,"
               "lockstep_timeouts_steady,hashes_equal,missing_snapshots,recovery_ms,"
               "snapshots_per_s,latency_median_ms,latency_p99_ms,snapshot_age_median_ms,"
               "snapshot_age_p99_ms,kbit_per_s,skipped_snapshots\n");
  if (!out.ok) return 2;
  std::FILE* csv = out.file;
  std::vector<Path> paths;
  for (const int one_way : options.one_way_ms)
    for (const int jitter : options.jitter_ms) paths.push_back({one_way, jitter, 0, 0});
  if (options.stall_ms > 0) {
    paths.push_back({options.stall_one_way_ms,
                     options.jitter_ms.empty() ? 0 : options.jitter_ms.back(), options.stall_ms,
                     options.stall_every_ms});
  }
  if (options.lockstep) {
    fmt::print("Lockstep ({} Hz, realtime pace, {})\n\n", options.tick_rate,
               options.lockstep_scene.name);
    fmt::print(
        "| clients | client | one-way ms | jitter ms | stall ms/every | ticks/s | input delay "
        "ticks | timeouts (steady) | hashes equal | missing | recovery ms |\n");
    fmt::print("|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const Path& path : paths)
      for (const int clients : options.lockstep_clients)
        for (const Behaviour b : {Behaviour::OnClock, Behaviour::AfterSnapshot})
          print_row(run_lockstep(options, clients, path, b), options.tick_rate, csv);
  }
  if (options.fixed) {
    fmt::print("\nFixed rate ({} Hz, {}, one driving bot)\n\n", options.tick_rate,
               options.fixed_scene_label);
    fmt::print(
        "| client | one-way ms | jitter ms | stall ms/every | snapshots/s | input->snapshot "
        "median ms | p99 ms | newest snapshot age median ms | p99 ms | kbit/s | window skips | "
        "input delay ticks |\n");
    fmt::print("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const Path& path : paths)
      for (const Behaviour b : {Behaviour::OnClock, Behaviour::AfterSnapshot})
        print_row(run_fixed(options, path, b), options.tick_rate, csv);
  }
  if (csv != nullptr) std::fclose(csv);
  return 0;
}

}  // namespace netbench
