#include "ops_http.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <system_error>
#include <utility>

#include "ops_http_request.h"

namespace server {
namespace {

const char* reason_phrase(int status) {
  switch (status) {
    case 200:
      return "OK";
    case 400:
      return "Bad Request";
    case 404:
      return "Not Found";
    case 405:
      return "Method Not Allowed";
    case 408:
      return "Request Timeout";
    case 429:
      return "Too Many Requests";
    case 431:
      return "Request Header Fields Too Large";
    case 503:
      return "Service Unavailable";
    default:
      return "Error";
  }
}

std::string response(int status, const std::string& body, const char* content_type,
                     bool with_body) {
  std::string out = "HTTP/1.1 " + std::to_string(status) + " " + reason_phrase(status) +
                    "\r\nContent-Type: " + content_type +
                    "\r\nContent-Length: " + std::to_string(body.size()) +
                    "\r\nConnection: close\r\n\r\n";
  if (with_body) out += body;
  return out;
}

AddressLimitsConfig request_rate(const OpsHttpLimits& limits) {
  AddressLimitsConfig config;
  config.connects_per_second = limits.requests_per_second;
  config.connect_burst = limits.request_burst;
  return config;
}

}  // namespace

struct OpsHttp::Connection {
  Connection(asio::ip::tcp::socket s, std::string from, std::uint64_t id, std::size_t max_header)
      : socket(std::move(s)),
        deadline(socket.get_executor()),
        address(std::move(from)),
        serial(id),
        request(max_header) {}
  asio::ip::tcp::socket socket;
  asio::steady_timer deadline;
  std::string address;
  std::uint64_t serial;
  OpsHttpRequest request;
  std::array<char, 1024> chunk{};
  std::string answer;
  bool answering = false;  // the request is in: not evicted, it leaves by itself
};

OpsHttp::OpsHttp(const std::string& bind, std::uint16_t port, const OpsHttpLimits& limits,
                 std::function<ServerStats()> stats, MetricsInfo info)
    : limits_(limits), stats_(std::move(stats)), info_(info), requests_(request_rate(limits)) {
  const std::string where = bind + ":" + std::to_string(port);
  std::error_code ec;
  const asio::ip::address address = asio::ip::make_address(bind, ec);
  if (ec) throw std::system_error(ec, "cannot serve metrics on " + where);
  const asio::ip::tcp::endpoint endpoint(address, port);
  acceptor_.open(endpoint.protocol(), ec);
  if (!ec) acceptor_.set_option(asio::ip::tcp::acceptor::reuse_address(true), ec);
  if (!ec) acceptor_.bind(endpoint, ec);
  if (!ec) acceptor_.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) throw std::system_error(ec, "cannot serve metrics on " + where);
  port_ = acceptor_.local_endpoint().port();
  accept_next();
  thread_ = std::thread([this] {
    for (;;) {
      try {
        io_.run();
        return;
      } catch (const std::exception& error) {
        spdlog::error("metrics endpoint: a handler failed: {}; serving on", error.what());
      }
    }
  });
}

OpsHttp::~OpsHttp() {
  stop();
  connections_.clear();
}

void OpsHttp::stop() {
  io_.stop();
  if (thread_.joinable()) thread_.join();
}

OpsHttpStats OpsHttp::counters() const {
  std::lock_guard<std::mutex> lock(counters_mutex_);
  return counters_;
}

void OpsHttp::accept_next() {
  acceptor_.async_accept([this](std::error_code ec, asio::ip::tcp::socket socket) {
    if (ec == asio::error::operation_aborted) return;
    if (!ec) on_accepted(std::move(socket));
    accept_next();
  });
}

void OpsHttp::on_accepted(asio::ip::tcp::socket socket) {
  std::error_code ec;
  const auto remote = socket.remote_endpoint(ec);
  if (ec) return;
  const std::string address = remote.address().to_string();
  if (requests_.on_accept(address, std::chrono::steady_clock::now()).verdict !=
      AddressLimits::Verdict::Allowed) {
    // Over its rate: one small answer if the socket takes it at once, nothing read.
    const std::string refusal = response(429, "too many requests\n", "text/plain", true);
    socket.non_blocking(true, ec);
    if (!ec) socket.write_some(asio::buffer(refusal), ec);
    socket.close(ec);
    count([](OpsHttpStats& s) {
      ++s.rate_limited;
      ++s.requests_answered;
    });
    return;
  }
  evict_for(address);
  const std::uint64_t serial = next_serial_++;
  auto connection =
      std::make_shared<Connection>(std::move(socket), address, serial, limits_.max_header_bytes);
  connections_.emplace(serial, connection);
  ++per_address_[address];
  count([&](OpsHttpStats& s) {
    s.open_connections = connections_.size();
    s.peak_open_connections = std::max(s.peak_open_connections, s.open_connections);
  });
  connection->deadline.expires_after(limits_.request_deadline);
  connection->deadline.async_wait([this, serial](std::error_code wait_error) {
    if (wait_error) return;
    const auto it = connections_.find(serial);
    if (it == connections_.end()) return;
    if (!it->second->answering) count([](OpsHttpStats& s) { ++s.deadline_expired; });
    close(serial);
  });
  read_more(connection);
}

void OpsHttp::evict_for(const std::string& address) {
  const auto own = per_address_.find(address);
  const bool address_full =
      own != per_address_.end() && own->second >= limits_.max_connections_per_address;
  const bool all_full = static_cast<int>(connections_.size()) >= limits_.max_connections;
  if (!address_full && !all_full) return;
  for (const auto& [serial, connection] : connections_) {
    if (connection->answering) continue;
    if (address_full && connection->address != address) continue;
    count([](OpsHttpStats& s) { ++s.evicted; });
    close(serial);
    return;
  }
}

void OpsHttp::read_more(const std::shared_ptr<Connection>& connection) {
  connection->socket.async_read_some(
      asio::buffer(connection->chunk), [this, connection](std::error_code ec, std::size_t bytes) {
        if (ec) {
          close(connection->serial);
          return;
        }
        const std::size_t before = connection->request.held_bytes();
        const OpsHttpRequest::State state =
            connection->request.feed(std::string_view(connection->chunk.data(), bytes));
        const std::size_t grown = connection->request.held_bytes() - before;
        count([grown](OpsHttpStats& s) {
          s.held_header_bytes += grown;
          s.peak_held_header_bytes = std::max(s.peak_held_header_bytes, s.held_header_bytes);
        });
        switch (state) {
          case OpsHttpRequest::State::Incomplete:
            read_more(connection);
            return;
          case OpsHttpRequest::State::HeaderTooLarge:
            count([](OpsHttpStats& s) { ++s.header_too_large; });
            answer(connection, 431, "request headers too large\n");
            return;
          case OpsHttpRequest::State::Malformed:
            count([](OpsHttpStats& s) { ++s.malformed; });
            answer(connection, 400, "bad request\n");
            return;
          case OpsHttpRequest::State::Complete:
            route(connection);
            return;
        }
      });
}

void OpsHttp::route(const std::shared_ptr<Connection>& connection) {
  const std::string& method = connection->request.method();
  const std::string& target = connection->request.target();
  if (method != "GET" && method != "HEAD") {
    answer(connection, 405, "only GET and HEAD\n");
  } else if (target == "/healthz") {
    answer(connection, 200, "ok\n");
  } else if (target == "/readyz") {
    const Readiness verdict = readiness(stats_(), info_, std::chrono::steady_clock::now());
    answer(connection, verdict.ready ? 200 : 503, verdict.reason + "\n");
  } else if (target == "/metrics") {
    answer(connection, 200, render_prometheus(stats_(), info_), "text/plain; version=0.0.4");
  } else {
    answer(connection, 404, "not found\n");
  }
}

void OpsHttp::answer(const std::shared_ptr<Connection>& connection, int status,
                     const std::string& body, const char* content_type) {
  connection->answering = true;
  connection->answer = response(status, body, content_type, connection->request.method() != "HEAD");
  count([](OpsHttpStats& s) { ++s.requests_answered; });
  // The deadline still runs: a peer that does not take its answer is closed then.
  asio::async_write(connection->socket, asio::buffer(connection->answer),
                    [this, connection](std::error_code, std::size_t) {
                      std::error_code ignored;
                      connection->socket.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
                      close(connection->serial);
                    });
}

void OpsHttp::close(std::uint64_t serial) {
  const auto it = connections_.find(serial);
  if (it == connections_.end()) return;
  const std::shared_ptr<Connection> connection = it->second;
  connections_.erase(it);
  if (const auto own = per_address_.find(connection->address);
      own != per_address_.end() && --own->second <= 0) {
    per_address_.erase(own);
  }
  std::error_code ignored;
  connection->deadline.cancel();
  connection->socket.close(ignored);
  const std::size_t held = connection->request.held_bytes();
  count([&](OpsHttpStats& s) {
    s.open_connections = connections_.size();
    s.held_header_bytes -= held;
  });
}

}  // namespace server
