#pragma once
// The operations endpoints over HTTP/1.1, on an Asio loop and a thread of their own,
// so that neither a long tick nor a flood on the game port delays a probe:
//   GET /healthz  200 "ok" while the process serves;
//   GET /readyz   200 when ready, 503 otherwise (metrics.h: readiness), with why;
//   GET /metrics  the Prometheus text format (metrics.h).
// One request per connection (the answer says Connection: close). What a stranger
// may hold here is bounded: connections in all and per address, each with one total
// deadline for its request and a cap on its header bytes (431 over it), and a rate
// of requests per address (429 over it). A new connection over a cap evicts the
// oldest one still reading its request (from the same address when that address is
// at its own cap), so a probe always gets in. docs/SERVER.md says why this is not a
// general HTTP library.
#include <asio.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "address_limits.h"
#include "metrics.h"

namespace server {

class OpsHttp {
 public:
  // Binds at once (port 0: a free one); throws std::system_error if it cannot.
  OpsHttp(const std::string& bind, std::uint16_t port, const OpsHttpLimits& limits,
          std::function<ServerStats()> stats, MetricsInfo info);
  ~OpsHttp();
  OpsHttp(const OpsHttp&) = delete;
  OpsHttp& operator=(const OpsHttp&) = delete;

  // Stops serving and joins the thread (the destructor does too): afterwards nothing
  // calls the stats callback.
  void stop();
  std::uint16_t port() const { return port_; }
  // A consistent copy, safe from any thread.
  OpsHttpStats counters() const;

 private:
  struct Connection;
  void accept_next();
  void on_accepted(asio::ip::tcp::socket socket);
  // Makes room for one more connection from `address`: closes the oldest of its own
  // when it is at its cap, else the oldest of all when all are taken.
  void evict_for(const std::string& address);
  void read_more(const std::shared_ptr<Connection>& connection);
  void answer(const std::shared_ptr<Connection>& connection, int status, const std::string& body,
              const char* content_type = "text/plain");
  void close(std::uint64_t serial);
  // The status and body of a complete request.
  void route(const std::shared_ptr<Connection>& connection);
  template <typename Update>
  void count(Update&& update) {
    std::lock_guard<std::mutex> lock(counters_mutex_);
    update(counters_);
  }

  OpsHttpLimits limits_;
  std::function<ServerStats()> stats_;
  MetricsInfo info_;
  asio::io_context io_;
  asio::ip::tcp::acceptor acceptor_{io_};
  std::uint16_t port_ = 0;
  // Open connections by accept order, so the first is the oldest.
  std::map<std::uint64_t, std::shared_ptr<Connection>> connections_;
  std::map<std::string, int> per_address_;
  std::uint64_t next_serial_ = 1;
  AddressLimits requests_;  // requests per address: one per connection
  mutable std::mutex counters_mutex_;
  OpsHttpStats counters_;
  std::thread thread_;
};

}  // namespace server
