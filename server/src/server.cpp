// The server's construction and its public face: the config's checks, the listening
// socket, the recorder, signals, the metrics endpoint and Agones; run, stop, stats.
// The rest of Server::Impl is split by job: server_connections.cpp (accepting,
// limits before Hello, closing), server_messages.cpp (dispatch), server_handshake.cpp
// (carrying out the Hello's decision, handshake.h), server_ticks.cpp (the tick loop),
// server_housekeeping.cpp (deadlines, the stats line, shutdown).
#include "server/server.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "server_impl.h"

namespace server {
namespace {

// Lines a stranger can cause, per cause: at most this many a second, the rest counted.
constexpr std::size_t kLogLinesPerSecond = 10;

void check_config(const ServerConfig& config) {
  if (config.max_clients < 1) throw std::invalid_argument("max_clients must be at least 1");
  if (config.max_spectators < 0) throw std::invalid_argument("max_spectators must be >= 0");
  if (config.max_message_bytes < 64) {
    throw std::invalid_argument("max_message_bytes must be at least 64");
  }
  if (config.max_snapshot_window < 1 || config.max_snapshot_window > wire::kMaxWindow) {
    throw std::invalid_argument("max_snapshot_window must be in [1, " +
                                std::to_string(wire::kMaxWindow) + "]");
  }
  if (config.heartbeat.count() <= 0) throw std::invalid_argument("heartbeat must be > 0");
  if (config.handshake_timeout.count() <= 0) {
    throw std::invalid_argument("handshake_timeout must be > 0");
  }
  if (config.max_pending < 1 || config.max_pending_per_address < 1) {
    throw std::invalid_argument("max_pending and max_pending_per_address must be at least 1");
  }
  if (config.max_hello_bytes < 64) throw std::invalid_argument("max_hello_bytes must be >= 64");
  if (config.idle_timeout.count() <= 0) throw std::invalid_argument("idle_timeout must be > 0");
  if (config.lockstep_timeout.count() <= 0) {
    throw std::invalid_argument("lockstep_timeout must be > 0");
  }
  if (config.steps_per_frame < 0 || config.steps_per_frame > 1000) {
    throw std::invalid_argument("steps_per_frame must be in [0, 1000] (0: the scene's)");
  }
  if (config.max_ticks_ahead < 1) throw std::invalid_argument("max_ticks_ahead must be >= 1");
  if (config.ticket_key && config.token) {
    throw std::invalid_argument(
        "a ticket key and an access token: give one (tickets replace the token)");
  }
  if (config.ticket_room.size() > ticket::kMaxRoomBytes) {
    throw std::invalid_argument("ticket_room is at most " + std::to_string(ticket::kMaxRoomBytes) +
                                " bytes");
  }
  if (config.lockstep_players < 0 || config.lockstep_players > config.max_clients) {
    throw std::invalid_argument("lockstep_players must be in [0, max_clients]");
  }
  if (config.lockstep_players > 0 && !config.lockstep) {
    throw std::invalid_argument("lockstep_players needs lockstep");
  }
  if (config.lockstep_max_timeouts < 0) {
    throw std::invalid_argument("lockstep_max_timeouts must be >= 0 (0: never drop)");
  }
  if (config.stats_log_interval.count() < 0) {
    throw std::invalid_argument("stats_log_interval must be >= 0 (0: no stats lines)");
  }
  if (config.failed_hellos_before_backoff < 1) {
    throw std::invalid_argument("failed_hellos_before_backoff must be at least 1");
  }
  if (config.hello_backoff.count() < 0 || config.hello_backoff_max < config.hello_backoff) {
    throw std::invalid_argument("need 0 <= hello_backoff <= hello_backoff_max");
  }
  if (config.seat_backoff.count() < 0) throw std::invalid_argument("seat_backoff must be >= 0");
  if (config.max_players_per_address < 0) {
    throw std::invalid_argument("max_players_per_address must be >= 0 (0: no cap)");
  }
  const OpsHttpLimits& http = config.metrics_limits;
  if (http.max_connections < 1 || http.max_connections_per_address < 1 ||
      http.request_deadline.count() <= 0 || http.max_header_bytes < 64 ||
      !(http.requests_per_second >= 0.0) || !std::isfinite(http.requests_per_second) ||
      !(http.request_burst >= 0.0) || !std::isfinite(http.request_burst)) {
    throw std::invalid_argument(
        "metrics limits: connections >= 1, deadline > 0, header bytes >= 64, finite rates >= 0");
  }
  for (const double rate :
       {config.connects_per_second, config.connect_burst, config.full_state_bytes_per_second,
        config.peer_bytes_per_second, config.peer_byte_burst, config.peer_messages_per_second,
        config.peer_message_burst}) {
    if (!(rate >= 0.0) || !std::isfinite(rate)) {
      throw std::invalid_argument("rate limits must be finite and >= 0 (0: unlimited)");
    }
  }
}

AddressLimitsConfig address_limits_config(const ServerConfig& config) {
  AddressLimitsConfig limits;
  limits.connects_per_second = config.connects_per_second;
  limits.connect_burst = config.connect_burst;
  limits.failures_before_backoff = config.failed_hellos_before_backoff;
  limits.backoff_base = config.hello_backoff;
  limits.backoff_max = config.hello_backoff_max;
  limits.seat_backoff = config.seat_backoff;
  return limits;
}

// Heartbeats in ticks: at least one.
std::uint64_t heartbeat_ticks(std::chrono::milliseconds heartbeat, double tick_rate) {
  const double ticks = std::round(static_cast<double>(heartbeat.count()) * tick_rate / 1000.0);
  return ticks < 1.0 ? 1 : static_cast<std::uint64_t>(ticks);
}

SimulationOptions simulation_options(const ServerConfig& config) {
  SimulationOptions options;
  options.tick_rate = config.tick_rate;
  options.max_ticks_ahead = config.max_ticks_ahead;
  return options;
}

// Before anything logs: the server's first lines already obey the config.
void apply_log_level(const ServerConfig& config) {
  if (config.log_level) set_log_level(*config.log_level);
}

}  // namespace

Server::Impl::Impl(ServerConfig config, scene::SceneDef scene)
    : config_((check_config(config), apply_log_level(config), std::move(config))),
      simulation_(std::move(scene), simulation_options(config_), config_.rules),
      acceptor_(io_),
      tick_timer_(io_),
      lockstep_timer_(io_),
      housekeeping_timer_(io_),
      accept_retry_timer_(io_),
      ws_accept_retry_timer_(io_),
      gate_(config_.lockstep_timeout),
      feeds_(wire::Predictor(simulation_.tick_rate(), simulation_.world().settings().gravity.x,
                             simulation_.world().settings().gravity.y),
             heartbeat_ticks(config_.heartbeat, simulation_.tick_rate()), config_.lockstep),
      address_limits_(address_limits_config(config_)),
      log_limiter_(kLogLinesPerSecond, std::chrono::seconds(1)),
      handshake_(config_),
      stragglers_(config_.lockstep_max_timeouts),
      input_timing_(std::chrono::duration_cast<std::chrono::nanoseconds>(
                        std::chrono::duration<double>(1.0 / simulation_.tick_rate())),
                    config_.lockstep_timeout),
      tick_period_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(1.0 / simulation_.tick_rate()))) {
  silence_protobuf_log();
  limits_.max_message_bytes = config_.max_message_bytes;
  limits_.max_hello_bytes = config_.max_hello_bytes;
  limits_.handshake_timeout = config_.handshake_timeout;
  limits_.max_queued_snapshots = config_.max_snapshot_window + 1;
  feeds_.size_windows(tick_period_, config_.max_snapshot_window);
  limits_.idle_timeout = config_.idle_timeout;
  limits_.close_linger = config_.close_linger;
  limits_.socket_send_buffer_bytes = config_.socket_send_buffer_bytes;
  limits_.full_state_bytes_per_second = config_.full_state_bytes_per_second;
  limits_.bytes_per_second = config_.peer_bytes_per_second;
  limits_.byte_burst = config_.peer_byte_burst;
  limits_.messages_per_second = config_.peer_messages_per_second;
  limits_.message_burst = config_.peer_message_burst;

  const std::string where = config_.bind + ":" + std::to_string(config_.port);
  std::error_code ec;
  const asio::ip::address address = asio::ip::make_address(config_.bind, ec);
  if (ec) throw std::system_error(ec, "cannot listen on " + where + ": bad address");
  const asio::ip::tcp::endpoint endpoint(address, config_.port);
  acceptor_.open(endpoint.protocol(), ec);
  if (ec) throw std::system_error(ec, "cannot listen on " + where);
  acceptor_.set_option(asio::ip::tcp::acceptor::reuse_address(true), ec);
  acceptor_.bind(endpoint, ec);
  if (ec) throw std::system_error(ec, "cannot listen on " + where);
  acceptor_.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) throw std::system_error(ec, "cannot listen on " + where);
  port_ = acceptor_.local_endpoint().port();
  if (config_.ws_port) listen_ws(address, *config_.ws_port);

  if (!config_.record_path.empty()) {
    RecordOptions record_options;
    record_options.lockstep = config_.lockstep;
    std::string error;
    std::unique_ptr<TickRecorder> recorder =
        TickRecorder::create(config_.record_path, simulation_.scene(), simulation_.tick_rate(),
                             simulation_.max_ticks_ahead(), record_options, &error);
    if (!recorder) throw std::invalid_argument("--record: " + error);
    simulation_.record_to(std::move(recorder));
  }

  if (config_.handle_signals) {
    signals_.emplace(io_, SIGINT, SIGTERM);
    signals_->async_wait([this](std::error_code wait_error, int signal_number) {
      if (wait_error) return;
      spdlog::info("signal {} received: shutting down", signal_number);
      begin_shutdown();
    });
  }
  update_stats([&](ServerStats& s) {
    s.last_state_hash = simulation_.world().state_hash();
    s.lockstep_started = handshake_.lobby_open();
  });
  if (config_.metrics_port) {
    MetricsInfo info;
    info.tick_rate = simulation_.tick_rate();
    info.lockstep = config_.lockstep;
    info.max_clients = static_cast<std::size_t>(config_.max_clients);
    metrics_ = std::make_unique<OpsHttp>(
        config_.metrics_bind, *config_.metrics_port, config_.metrics_limits,
        [this] { return stats(); }, info);
  }
  if (config_.agones_sdk_port) {
    AgonesSdkConfig agones;
    agones.port = *config_.agones_sdk_port;
    agones.health_period = config_.agones_health_period;
    agones.capacity = handshake_.seats().size();
    agones_ = std::make_unique<AgonesSdk>(agones, [this] { return stats(); });
  }
}

Server::Impl::~Impl() {
  // The HTTP threads read stats_ (and stats() reads metrics_): stop them first.
  agones_.reset();
  if (metrics_) metrics_->stop();
  metrics_.reset();
  // Sessions hold sockets of io_; drop them before io_ goes.
  sessions_.clear();
}

void Server::Impl::run() {
  asio::post(io_, [this] {
    if (stopping_) return;
    do_accept();
    if (ws_acceptor_) do_ws_accept();
    arm_housekeeping();
    if (!config_.lockstep) start_fixed_ticks();
    if (agones_) agones_->ready();
  });
  // A handler that throws past its session's own catch (session.cpp) must not end
  // every match: log it and go on serving.
  for (;;) {
    try {
      io_.run();
      try {
        simulation_.end();  // the game rules' on_end
      } catch (const std::exception& error) {
        spdlog::error("the game rules' on_end failed: {}", error.what());
      }
      return;
    } catch (const std::exception& error) {
      spdlog::error("a handler failed: {}; serving on", error.what());
    }
  }
}

void Server::Impl::stop() {
  asio::post(io_, [this] { begin_shutdown(); });
}

ServerStats Server::Impl::stats() const {
  ServerStats copy;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    copy = stats_;
  }
  if (metrics_) copy.ops_http = metrics_->counters();
  return copy;
}

// ---- the public face ----

Server::Server(ServerConfig config, scene::SceneDef scene)
    : impl_(std::make_shared<Impl>(std::move(config), std::move(scene))) {}
Server::~Server() = default;
std::uint16_t Server::port() const { return impl_->port(); }
std::uint16_t Server::ws_port() const { return impl_->ws_port(); }
void Server::run() { impl_->run(); }
void Server::stop() { impl_->stop(); }
ServerStats Server::stats() const { return impl_->stats(); }
std::uint16_t Server::metrics_port() const { return impl_->metrics_port(); }

}  // namespace server
