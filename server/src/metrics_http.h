#pragma once
// The operations endpoints over HTTP, on a thread of their own (cpp-httplib):
//   GET /healthz  200 "ok" while the process serves;
//   GET /readyz   200 when ready, 503 otherwise (metrics.h: readiness), with why;
//   GET /metrics  the Prometheus text format (metrics.h).
// They read only the stats callback (a consistent copy under the server's mutex).
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "metrics.h"

namespace httplib {
class Server;
}

namespace server {

class MetricsHttp {
 public:
  // Binds at once (port 0: a free one); throws std::system_error if it cannot.
  MetricsHttp(const std::string& bind, std::uint16_t port, std::function<ServerStats()> stats,
              MetricsInfo info);
  ~MetricsHttp();
  MetricsHttp(const MetricsHttp&) = delete;
  MetricsHttp& operator=(const MetricsHttp&) = delete;

  std::uint16_t port() const { return port_; }

 private:
  std::unique_ptr<httplib::Server> http_;
  std::uint16_t port_ = 0;
  std::thread thread_;
};

}  // namespace server
