#pragma once
// What the operations endpoints say, computed from a ServerStats copy alone, so
// that they never reach into the tick: the Prometheus text exposition of
// /metrics and the verdict of /readyz. Socket-free; tests feed it stats by hand.
#include <chrono>
#include <string>

#include "server/server.h"

namespace server {

// What the stats do not carry: the server's fixed settings.
struct MetricsInfo {
  double tick_rate = 60.0;
  bool lockstep = false;
  std::size_t max_clients = 0;
};

// Prometheus text format 0.0.4: every metric's HELP and TYPE, names prefixed
// physics_, counters suffixed _total.
std::string render_prometheus(const ServerStats& stats, const MetricsInfo& info);

struct Readiness {
  bool ready = false;
  std::string reason;  // one line: why (not) ready
};
// Ready while not shutting down and stepping on time: with the fixed timestep, a
// tick stepped within the last max(1 s, 10 periods), and the last tick's step and
// encoding within its period (not overrunning). Lockstep ticks wait for the
// players by design, so a lockstep server is ready while it listens.
Readiness readiness(const ServerStats& stats, const MetricsInfo& info,
                    std::chrono::steady_clock::time_point now);

}  // namespace server
