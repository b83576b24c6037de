#include "metrics_http.h"

#include <httplib.h>

#include <chrono>
#include <system_error>
#include <utility>

namespace server {

MetricsHttp::MetricsHttp(const std::string& bind, std::uint16_t port,
                         std::function<ServerStats()> stats, MetricsInfo info)
    : http_(std::make_unique<httplib::Server>()) {
  // A scrape or a probe every few seconds: two workers are plenty (the default is
  // eight or more), and they never touch the tick.
  http_->new_task_queue = [] { return new httplib::ThreadPool(2); };
  http_->Get("/healthz", [](const httplib::Request&, httplib::Response& response) {
    response.set_content("ok\n", "text/plain");
  });
  http_->Get("/readyz", [stats, info](const httplib::Request&, httplib::Response& response) {
    const Readiness verdict = readiness(stats(), info, std::chrono::steady_clock::now());
    response.status = verdict.ready ? 200 : 503;
    response.set_content(verdict.reason + "\n", "text/plain");
  });
  http_->Get("/metrics", [stats, info](const httplib::Request&, httplib::Response& response) {
    response.set_content(render_prometheus(stats(), info), "text/plain; version=0.0.4");
  });
  const int bound = port == 0 ? http_->bind_to_any_port(bind)
                              : (http_->bind_to_port(bind, port) ? static_cast<int>(port) : -1);
  if (bound <= 0) {
    throw std::system_error(std::make_error_code(std::errc::address_in_use),
                            "cannot serve metrics on " + bind + ":" + std::to_string(port));
  }
  port_ = static_cast<std::uint16_t>(bound);
  thread_ = std::thread([this] { http_->listen_after_bind(); });
}

MetricsHttp::~MetricsHttp() {
  // stop() does nothing until the listening loop has begun: let it begin (it does so
  // at once; the bound only guards against a thread that never started).
  for (int i = 0; i < 2000 && !http_->is_running(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  http_->stop();
  if (thread_.joinable()) thread_.join();
}

}  // namespace server
