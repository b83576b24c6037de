// /metrics and /readyz from a ServerStats copy: the Prometheus text holds what the
// stats say, and readiness follows ticks and shutdown.
#include "metrics.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace {

using namespace std::chrono_literals;

// The value of the sample line that starts with `series` + ' '; "" if none.
std::string sample(const std::string& text, const std::string& series) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind(series + ' ', 0) == 0) return line.substr(series.size() + 1);
  }
  return "";
}

server::ServerStats some_stats() {
  server::ServerStats s;
  s.ticks_stepped = 42;
  s.current_tick = 42;
  s.connected_clients = 2;
  s.spectators = 1;
  s.lobby_clients = 0;
  s.open_connections = 4;  // one more: a connection still handshaking
  s.bytes_sent = 1234;
  s.bytes_received = 567;
  s.lockstep_timeouts = 3;
  s.skipped_snapshots = 5;
  s.tick_overruns = 1;
  s.dropped[server::DropReason::ClientBye] = 2;
  s.dropped[server::DropReason::Idle] = 1;
  s.tick_seconds_buckets[0] = 40;     // <= 62.5 us
  s.tick_seconds_buckets[4] = 1;      // (0.5, 1] ms
  s.tick_seconds_buckets.back() = 1;  // over the last bound
  s.total_tick_seconds = 0.25;
  return s;
}

TEST(Metrics, PrometheusTextCarriesEveryFigureOfTheStats) {
  server::MetricsInfo info;
  info.tick_rate = 60.0;
  info.max_clients = 64;
  const std::string text = server::render_prometheus(some_stats(), info);
  EXPECT_EQ(sample(text, "physics_ticks_total"), "42");
  EXPECT_EQ(sample(text, "physics_clients{state=\"playing\"}"), "2");
  EXPECT_EQ(sample(text, "physics_clients{state=\"spectating\"}"), "1");
  EXPECT_EQ(sample(text, "physics_clients{state=\"pending\"}"), "1");
  EXPECT_EQ(sample(text, "physics_bytes_sent_total"), "1234");
  EXPECT_EQ(sample(text, "physics_bytes_received_total"), "567");
  EXPECT_EQ(sample(text, "physics_lockstep_timeouts_total"), "3");
  EXPECT_EQ(sample(text, "physics_snapshots_skipped_total"), "5");
  EXPECT_EQ(sample(text, "physics_tick_overruns_total"), "1");
  EXPECT_EQ(sample(text, "physics_sessions_ended_total{reason=\"said_bye\"}"), "2");
  EXPECT_EQ(sample(text, "physics_sessions_ended_total{reason=\"idle_nothing_received\"}"), "1");
  // The histogram is cumulative and its count is every tick.
  EXPECT_EQ(sample(text, "physics_tick_seconds_bucket{le=\"6.25e-05\"}"), "40");
  EXPECT_EQ(sample(text, "physics_tick_seconds_bucket{le=\"0.001\"}"), "41");
  EXPECT_EQ(sample(text, "physics_tick_seconds_bucket{le=\"0.128\"}"), "41");
  EXPECT_EQ(sample(text, "physics_tick_seconds_bucket{le=\"+Inf\"}"), "42");
  EXPECT_EQ(sample(text, "physics_tick_seconds_count"), "42");
  EXPECT_EQ(sample(text, "physics_tick_seconds_sum"), "0.25");
  EXPECT_NE(text.find("# TYPE physics_tick_seconds histogram\n"), std::string::npos);
  EXPECT_NE(text.find("# TYPE physics_ticks_total counter\n"), std::string::npos);
}

TEST(Metrics, ReadyWhileTicksStepOnTimeNotBeforeNorAfter) {
  server::MetricsInfo info;
  info.tick_rate = 60.0;
  server::ServerStats stats;
  const auto now = std::chrono::steady_clock::now();
  EXPECT_FALSE(server::readiness(stats, info, now).ready);  // no tick yet
  stats.ticks_stepped = 10;
  stats.last_tick_at = now - 20ms;
  EXPECT_TRUE(server::readiness(stats, info, now).ready);
  stats.last_tick_at = now - 2s;  // stalled: more than max(1 s, 10 periods)
  const server::Readiness stalled = server::readiness(stats, info, now);
  EXPECT_FALSE(stalled.ready);
  EXPECT_NE(stalled.reason.find("last tick"), std::string::npos);
  stats.last_tick_at = now;
  stats.last_tick_seconds = 2.0 / 60.0;  // the last tick took two periods: overrunning
  const server::Readiness overrunning = server::readiness(stats, info, now);
  EXPECT_FALSE(overrunning.ready);
  EXPECT_NE(overrunning.reason.find("overrunning"), std::string::npos);
  stats.last_tick_seconds = 0.5 / 60.0;
  EXPECT_TRUE(server::readiness(stats, info, now).ready);
  stats.shutting_down = true;
  EXPECT_FALSE(server::readiness(stats, info, now).ready);
}

TEST(Metrics, LockstepIsReadyWithoutTicksUntilShutdown) {
  server::MetricsInfo info;
  info.lockstep = true;
  server::ServerStats stats;
  EXPECT_TRUE(server::readiness(stats, info, std::chrono::steady_clock::now()).ready);
  stats.shutting_down = true;
  EXPECT_FALSE(server::readiness(stats, info, std::chrono::steady_clock::now()).ready);
}

}  // namespace
