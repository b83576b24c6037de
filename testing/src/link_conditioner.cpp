#include "physics_testing/link_conditioner.h"

#include <asio/io_context.hpp>
#include <asio/ip/address.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/post.hpp>
#include <asio/steady_timer.hpp>
#include <cmath>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <utility>

#include "relay_connection.h"

namespace physics_testing {

namespace {

// An accept that failed for want of resources (descriptors) is tried again this much
// later, not at once in a loop.
constexpr std::chrono::milliseconds kAcceptRetry{100};

// The address of `host`, which must be a loopback address ("localhost" is 127.0.0.1):
// the conditioner relays for tests on this machine and must not become an open relay.
asio::ip::address loopback_address(const std::string& host, const char* what) {
  std::error_code error;
  const asio::ip::address address =
      asio::ip::make_address(host == "localhost" ? "127.0.0.1" : host, error);
  if (error) {
    throw std::invalid_argument(std::string(what) + " is not an IP address: '" + host + "'");
  }
  if (!address.is_loopback()) {
    throw std::invalid_argument(std::string(what) + " " + host +
                                " is not a loopback address (127.0.0.0/8 or ::1)");
  }
  return address;
}

void check_direction(const PathDirection& direction, const std::string& name) {
  if (direction.latency.count() < 0) throw std::invalid_argument(name + ".latency is negative");
  if (direction.jitter.count() < 0) throw std::invalid_argument(name + ".jitter is negative");
  const double bandwidth = direction.bandwidth_bytes_per_second;
  if (!std::isfinite(bandwidth) || bandwidth < 0.0) {
    throw std::invalid_argument(name + ".bandwidth_bytes_per_second must be finite and >= 0");
  }
}

void check_path(const PathConfig& path) {
  check_direction(path.to_server, "to_server");
  check_direction(path.to_client, "to_client");
  const PathStalls& stalls = path.stalls;
  if (stalls.duration.count() < 0) throw std::invalid_argument("stalls.duration is negative");
  if (!std::isfinite(stalls.per_second) || stalls.per_second < 0.0) {
    throw std::invalid_argument("stalls.per_second must be finite and >= 0");
  }
  if (stalls.every.count() < 0) throw std::invalid_argument("stalls.every is negative");
  for (const std::chrono::milliseconds at : stalls.at) {
    if (at.count() < 0) throw std::invalid_argument("stalls.at has a negative time");
  }
  // Stalls that follow each other without a gap would hold the stream for good.
  if (stalls.every.count() > 0 && stalls.every <= stalls.duration) {
    throw std::invalid_argument("stalls.every must be longer than stalls.duration");
  }
  const double seconds = std::chrono::duration<double>(stalls.duration).count();
  if (stalls.per_second * seconds >= 1.0) {
    throw std::invalid_argument(
        "stalls.per_second times stalls.duration must be below 1 (stalls would overlap "
        "into one)");
  }
}

}  // namespace

PathConfig symmetric_path(std::chrono::microseconds one_way, std::chrono::microseconds jitter) {
  PathConfig path;
  path.to_server.latency = one_way;
  path.to_server.jitter = jitter;
  path.to_client = path.to_server;
  return path;
}

LinkConditionerConfig relay_to(std::uint16_t port, PathConfig path) {
  LinkConditionerConfig config;
  config.target_port = port;
  config.path = std::move(path);
  return config;
}

struct LinkConditioner::Impl {
  explicit Impl(LinkConditionerConfig settings) : config(std::move(settings)) {}

  void accept();
  void close_all();

  LinkConditionerConfig config;  // its path is the io thread's
  std::shared_ptr<RelayCounters> counters = std::make_shared<RelayCounters>();
  asio::io_context io;
  asio::ip::tcp::acceptor acceptor{io};
  asio::steady_timer accept_retry{io};
  asio::ip::tcp::endpoint target;
  std::uint16_t port = 0;
  std::vector<std::weak_ptr<RelayConnection>> open;
  std::thread thread;
};

void LinkConditioner::Impl::accept() {
  acceptor.async_accept([this](const asio::error_code& error, asio::ip::tcp::socket socket) {
    if (error == asio::error::operation_aborted || !acceptor.is_open()) return;
    if (error) {
      accept_retry.expires_after(kAcceptRetry);
      accept_retry.async_wait([this](const asio::error_code& waited) {
        if (!waited) accept();
      });
      return;
    }
    const std::uint64_t index = counters->connections++;
    auto connection = std::make_shared<RelayConnection>(std::move(socket), index, config.path,
                                                        config.max_held_bytes, counters);
    connection->start(target);
    std::erase_if(open, [](const std::weak_ptr<RelayConnection>& c) { return c.expired(); });
    open.push_back(connection);
    accept();
  });
}

void LinkConditioner::Impl::close_all() {
  asio::error_code ignored;
  acceptor.close(ignored);
  accept_retry.cancel();
  for (const std::weak_ptr<RelayConnection>& weak : open) {
    if (const auto connection = weak.lock()) connection->close();
  }
}

LinkConditioner::LinkConditioner(LinkConditionerConfig config)
    : impl_(std::make_unique<Impl>(std::move(config))) {
  Impl& impl = *impl_;
  const asio::ip::address listen = loopback_address(impl.config.listen_host, "listen_host");
  const asio::ip::address target = loopback_address(impl.config.target_host, "target_host");
  if (impl.config.target_port == 0) throw std::invalid_argument("target_port is 0");
  if (impl.config.max_held_bytes == 0) throw std::invalid_argument("max_held_bytes is 0");
  check_path(impl.config.path);
  impl.target = asio::ip::tcp::endpoint(target, impl.config.target_port);
  const asio::ip::tcp::endpoint endpoint(listen, impl.config.listen_port);
  try {
    impl.acceptor.open(endpoint.protocol());
    impl.acceptor.set_option(asio::ip::tcp::acceptor::reuse_address(true));
    impl.acceptor.bind(endpoint);
    impl.acceptor.listen();
  } catch (const std::system_error& error) {
    throw std::runtime_error("link conditioner cannot listen on " + impl.config.listen_host + ":" +
                             std::to_string(impl.config.listen_port) + ": " + error.what());
  }
  impl.port = impl.acceptor.local_endpoint().port();
  impl.accept();
  impl.thread = std::thread([&impl] { impl.io.run(); });
}

LinkConditioner::~LinkConditioner() {
  asio::post(impl_->io, [impl = impl_.get()] {
    impl->close_all();
    impl->io.stop();
  });
  impl_->thread.join();
}

std::uint16_t LinkConditioner::port() const { return impl_->port; }

void LinkConditioner::set_path(const PathConfig& path) {
  check_path(path);
  asio::post(impl_->io, [impl = impl_.get(), path] {
    impl->config.path = path;
    for (const std::weak_ptr<RelayConnection>& weak : impl->open) {
      if (const auto connection = weak.lock()) connection->set_path(path);
    }
  });
}

LinkStats LinkConditioner::stats() const {
  const RelayCounters& counters = *impl_->counters;
  LinkStats stats;
  stats.connections = counters.connections.load();
  stats.bytes_to_server = counters.bytes_to_server.load();
  stats.bytes_to_client = counters.bytes_to_client.load();
  stats.stalls = counters.stalls.load();
  stats.held_bytes_peak = counters.held_bytes_peak.load();
  return stats;
}

}  // namespace physics_testing
