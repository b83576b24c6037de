#include "server/server.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "client_ids.h"
#include "server_impl.h"
#include "wire/messages.h"
#include "wire/view_settings.h"

namespace server {
namespace {

constexpr std::size_t kMaxClientNameBytes = 64;
constexpr auto kHousekeepingPeriod = std::chrono::milliseconds(100);
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
  for (const double rate :
       {config.connects_per_second, config.connect_burst, config.peer_bytes_per_second,
        config.peer_byte_burst, config.peer_messages_per_second, config.peer_message_burst}) {
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
  return limits;
}

// The ways a Hello can fail that count against its address: a stranger guessing or
// fuzzing. Not the server's own limits (full, no spawn), nor a client that leaves.
bool is_failed_hello(DropReason reason) {
  switch (reason) {
    case DropReason::MessageTooLarge:
    case DropReason::Malformed:
    case DropReason::ProtocolVersion:
    case DropReason::BadToken:
    case DropReason::UnexpectedMessage:
    case DropReason::InvalidView:
    case DropReason::InvalidSubscription:
    case DropReason::HandshakeTimeout:
      return true;
    default:
      return false;
  }
}

// For the log: a client's name is whatever it sent; keep it printable and short.
std::string printable_name(const std::string& raw) {
  std::string name = raw.substr(0, kMaxClientNameBytes);
  for (char& c : name) {
    if (c < 0x20 || c == 0x7F) c = '?';
  }
  return name;
}

// Compares without stopping at the first difference, so the time taken does not
// tell an attacker how much of the token was right.
bool same_token(const std::string& given, const std::string& expected) {
  unsigned char difference = given.size() == expected.size() ? 0 : 1;
  for (std::size_t i = 0; i < given.size(); ++i) {
    difference |= static_cast<unsigned char>(given[i] ^ expected[i % (expected.size() + 1)]);
  }
  return difference == 0;
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

}  // namespace

const char* to_string(DropReason reason) {
  switch (reason) {
    case DropReason::ClientBye:
      return "said bye";
    case DropReason::Disconnected:
      return "disconnected";
    case DropReason::MessageTooLarge:
      return "message too large";
    case DropReason::Malformed:
      return "malformed message";
    case DropReason::ProtocolVersion:
      return "wrong protocol version";
    case DropReason::BadToken:
      return "bad token";
    case DropReason::ServerFull:
      return "server full";
    case DropReason::NoSpawn:
      return "no free spawn point";
    case DropReason::UnexpectedMessage:
      return "unexpected message";
    case DropReason::Idle:
      return "idle (nothing received)";
    case DropReason::TooSlow:
      return "too slow (not reading)";
    case DropReason::ShuttingDown:
      return "server shutting down";
    case DropReason::InvalidView:
      return "invalid view settings";
    case DropReason::HandshakeTimeout:
      return "no Hello in time";
    case DropReason::TooManyPending:
      return "too many connections not joined";
    case DropReason::AddressLimited:
      return "address refused (failed Hellos or connecting too fast)";
    case DropReason::InternalError:
      return "internal error handling its message";
    case DropReason::SeatTaken:
      return "seat taken";
    case DropReason::SeatOutOfRange:
      return "seat out of range";
    case DropReason::LockstepStraggler:
      return "lockstep straggler (missed too many ticks)";
    case DropReason::InvalidSubscription:
      return "invalid contact subscription";
  }
  return "unknown";
}

std::uint64_t ServerStats::dropped_total() const {
  std::uint64_t total = 0;
  for (const auto& [reason, count] : dropped) total += count;
  return total;
}

std::uint64_t ServerStats::dropped_by_fault() const {
  std::uint64_t total = 0;
  for (const auto& [reason, count] : dropped) {
    if (reason != DropReason::ClientBye && reason != DropReason::ShuttingDown) total += count;
  }
  return total;
}

Server::Impl::Impl(ServerConfig config, scene::SceneDef scene)
    : config_((check_config(config), std::move(config))),
      simulation_(std::move(scene), simulation_options(config_)),
      acceptor_(io_),
      tick_timer_(io_),
      lockstep_timer_(io_),
      housekeeping_timer_(io_),
      accept_retry_timer_(io_),
      gate_(config_.lockstep_timeout),
      feeds_(wire::Predictor(simulation_.tick_rate(), simulation_.world().settings().gravity.x,
                             simulation_.world().settings().gravity.y),
             heartbeat_ticks(config_.heartbeat, simulation_.tick_rate()), config_.lockstep),
      address_limits_(address_limits_config(config_)),
      log_limiter_(kLogLinesPerSecond, std::chrono::seconds(1)),
      seats_(static_cast<std::uint32_t>(config_.lockstep_players > 0 ? config_.lockstep_players
                                                                     : config_.max_clients)),
      lobby_open_(config_.lockstep_players == 0),
      stragglers_(config_.lockstep_max_timeouts),
      tick_period_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(1.0 / simulation_.tick_rate()))) {
  silence_protobuf_log();
  limits_.max_message_bytes = config_.max_message_bytes;
  limits_.max_hello_bytes = config_.max_hello_bytes;
  limits_.handshake_timeout = config_.handshake_timeout;
  limits_.max_queued_snapshots = config_.max_snapshot_window + 1;
  limits_.idle_timeout = config_.idle_timeout;
  limits_.close_linger = config_.close_linger;
  limits_.socket_send_buffer_bytes = config_.socket_send_buffer_bytes;
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
    s.lockstep_started = lobby_open_;
  });
  if (config_.metrics_port) {
    MetricsInfo info;
    info.tick_rate = simulation_.tick_rate();
    info.lockstep = config_.lockstep;
    info.max_clients = static_cast<std::size_t>(config_.max_clients);
    metrics_ = std::make_unique<MetricsHttp>(
        config_.bind, *config_.metrics_port, [this] { return stats(); }, info);
  }
  if (config_.agones_sdk_port) {
    AgonesSdkConfig agones;
    agones.port = *config_.agones_sdk_port;
    agones.health_period = config_.agones_health_period;
    agones.capacity = seats_.size();
    agones_ = std::make_unique<AgonesSdk>(agones, [this] { return stats(); });
  }
}

Server::Impl::~Impl() {
  // The HTTP threads read stats_: stop them first.
  agones_.reset();
  metrics_.reset();
  // Sessions hold sockets of io_; drop them before io_ goes.
  sessions_.clear();
}

void Server::Impl::run() {
  asio::post(io_, [this] {
    if (stopping_) return;
    do_accept();
    arm_housekeeping();
    if (!config_.lockstep) start_fixed_ticks();
    if (agones_) agones_->ready();
  });
  // A handler that throws past its session's own catch (session.cpp) must not end
  // every match: log it and go on serving.
  for (;;) {
    try {
      io_.run();
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
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

// ---- connections ----

void Server::Impl::do_accept() {
  acceptor_.async_accept([this](std::error_code ec, asio::ip::tcp::socket socket) {
    if (stopping_ || ec == asio::error::operation_aborted) return;
    if (ec) {
      // Out of descriptors, typically: wait a little rather than spin on the error.
      spdlog::warn("accept failed: {}", ec.message());
      accept_retry_timer_.expires_after(std::chrono::milliseconds(100));
      accept_retry_timer_.async_wait([this](std::error_code wait_error) {
        if (!wait_error && !stopping_) do_accept();
      });
      return;
    }
    update_stats([](ServerStats& s) { ++s.connections_accepted; });
    std::error_code endpoint_error;
    const auto remote = socket.remote_endpoint(endpoint_error);
    if (!endpoint_error) {
      const std::string address = remote.address().to_string();
      const AddressLimits::Decision decision =
          address_limits_.on_accept(address, std::chrono::steady_clock::now());
      if (decision.verdict != AddressLimits::Verdict::Allowed) {
        const auto retry =
            std::chrono::ceil<std::chrono::milliseconds>(decision.retry_after).count();
        refuse_at_accept(socket, decision.verdict == AddressLimits::Verdict::BackingOff
                                     ? "too many failed Hellos from " + address + "; retry in " +
                                           std::to_string(retry) + " ms"
                                     : "too many connections from " + address + "; retry in " +
                                           std::to_string(retry) + " ms");
        do_accept();
        return;
      }
    }
    const std::uint32_t id = take_free_id(
        next_client_id_, [this](std::uint32_t live) { return sessions_.count(live) > 0; });
    auto session = std::make_shared<Session>(std::move(socket), id, *this, limits_);
    sessions_.emplace(id, session);
    publish_connection_counts();
    if (log_admits("connection")) spdlog::info("connection {} from {}", id, session->peer());
    session->start();
    refuse_if_too_many_pending(*session);
    do_accept();
  });
}

// Connections that have not joined have caps of their own, in all and per address,
// so that a stranger's silent sockets never take a player's seat (and each is closed
// at the handshake deadline anyway).
void Server::Impl::refuse_if_too_many_pending(Session& fresh) {
  std::size_t pending = 0;
  std::size_t from_address = 0;
  for (const auto& [id, session] : sessions_) {
    if (session->joined() || session->closing()) continue;
    ++pending;
    if (session->address() == fresh.address()) ++from_address;
  }
  if (pending > static_cast<std::size_t>(config_.max_pending)) {
    fresh.close_with_error(
        physics::wire::ERROR_SERVER_FULL,
        "too many connections still handshaking (" + std::to_string(config_.max_pending) + ")",
        DropReason::TooManyPending);
  } else if (from_address > static_cast<std::size_t>(config_.max_pending_per_address)) {
    fresh.close_with_error(physics::wire::ERROR_SERVER_FULL,
                           "too many connections still handshaking from " + fresh.address() + " (" +
                               std::to_string(config_.max_pending_per_address) + ")",
                           DropReason::TooManyPending);
  }
}

void Server::Impl::refuse_at_accept(asio::ip::tcp::socket& socket, const std::string& text) {
  update_stats([](ServerStats& s) { ++s.dropped[DropReason::AddressLimited]; });
  if (log_admits("refused at accept")) spdlog::info("refused a connection: {}", text);
  std::error_code ignored;
  socket.non_blocking(true, ignored);
  const std::string frame =
      wire::encode_frame(wire::make_error(physics::wire::ERROR_RATE_LIMITED, text, true));
  socket.write_some(asio::buffer(frame), ignored);
  socket.shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
  socket.close(ignored);
}

bool Server::Impl::log_admits(const char* cause) {
  if (log_limiter_.admit(cause, std::chrono::steady_clock::now())) return true;
  update_stats([](ServerStats& s) { ++s.suppressed_log_lines; });
  return false;
}

void Server::Impl::on_throttled(Session& session) {
  update_stats([](ServerStats& s) { ++s.throttled_reads; });
  if (log_admits("over its rate")) {
    spdlog::info("connection {} ({}) is over its byte or message rate: reading paused",
                 session.id(), session.peer());
  }
}

void Server::Impl::on_handler_failed(Session& session, const char* what) {
  if (log_admits("handler failed")) {
    spdlog::error("handling a message of connection {} ({}) failed: {}; closing it", session.id(),
                  session.peer(), what);
  }
}

void Server::Impl::on_closed(Session& session, DropReason reason) {
  const std::uint32_t id = session.id();
  feeds_.leave(id);  // a subscription made by a Hello that then failed, too
  if (!session.joined() && is_failed_hello(reason)) {
    address_limits_.on_failed_hello(session.address(), std::chrono::steady_clock::now());
    update_stats([](ServerStats& s) { ++s.failed_hellos; });
  }
  if (session.joined() && spectators_.erase(id) > 0) {
    feeds_.leave(id);
    --spectator_count_;
    spdlog::info("spectator {} '{}' ({}) left: {}", id, session.name(), session.peer(),
                 to_string(reason));
  } else if (session.joined() && lobby_.erase(id) > 0) {
    seats_.release(id);
    spdlog::info("client {} '{}' ({}) left the lobby: {}", id, session.name(), session.peer(),
                 to_string(reason));
  } else if (session.joined()) {
    // A straggler has left the world already (drop_stragglers).
    if (simulation_.leave(id)) {
      feeds_.leave(id);
      --joined_count_;
    }
    seats_.release(id);
    stragglers_.forget(id);
    told_clamped_.erase(id);
    spdlog::info("client {} '{}' ({}) left: {}", id, session.name(), session.peer(),
                 to_string(reason));
  } else if (log_admits("closed before joining")) {
    spdlog::info("connection {} ({}) closed before joining: {}", id, session.peer(),
                 to_string(reason));
  }
  update_stats([&](ServerStats& s) { ++s.dropped[reason]; });
  sessions_.erase(id);
  publish_connection_counts();
  // One client fewer may be all the lockstep gate was waiting for. Posted, because
  // this can run in the middle of a broadcast.
  if (config_.lockstep) schedule_lockstep();
  if (config_.shutdown_after_match && config_.lockstep_players > 0 && lobby_open_ &&
      joined_count_ == 0 && !stopping_) {
    spdlog::info("match over: every player has left");
    asio::post(io_, [this] { begin_shutdown(); });
  }
}

void Server::Impl::on_bytes(std::size_t sent, std::size_t received) {
  update_stats([&](ServerStats& s) {
    s.bytes_sent += sent;
    s.bytes_received += received;
  });
}

void Server::Impl::publish_connection_counts() {
  update_stats([&](ServerStats& s) {
    s.connected_clients = joined_count_;
    s.lobby_clients = lobby_.size();
    s.spectators = spectator_count_;
    s.open_connections = sessions_.size();
  });
}

// ---- messages ----

void Server::Impl::on_message(Session& session, physics::wire::ClientMessage& message) {
  using Kind = physics::wire::ClientMessage::KindCase;
  // PROTOCOL.md 3.1: the first message must be Hello. Anything else before it (a
  // Ping included: it must not keep a connection that never joined alive) is fatal;
  // Bye closes quietly, and an empty envelope is malformed (below).
  const Kind kind = message.kind_case();
  if (!session.joined() && kind != Kind::kHello && kind != Kind::kBye &&
      kind != Kind::KIND_NOT_SET) {
    session.close_with_error(physics::wire::ERROR_UNEXPECTED_MESSAGE,
                             "a message before Hello: the first message must be Hello",
                             DropReason::UnexpectedMessage);
    return;
  }
  switch (kind) {
    case Kind::kHello:
      on_hello(session, message.hello());
      return;
    case Kind::kInput:
      if (spectators_.count(session.id()) > 0) {
        session.send(wire::make_error(physics::wire::ERROR_SPECTATOR_INPUT,
                                      "a spectator has no body to move; input dropped", false));
        return;
      }
      on_input(session, message.input());
      return;
    case Kind::kPing: {
      physics::wire::ServerMessage reply;
      physics::wire::Pong& pong = *reply.mutable_pong();
      pong.set_nonce(message.ping().nonce());
      pong.set_client_time_ns(message.ping().client_time_ns());
      pong.set_server_tick(simulation_.current_tick());
      session.send(reply);
      return;
    }
    case Kind::kAck:
      on_ack(session, message.ack());
      return;
    case Kind::kFullStateRequest:
      on_full_state_request(session);
      return;
    case Kind::kBye:
      spdlog::info("client {} says bye: {}", session.id(), printable_name(message.bye().reason()));
      session.close_now(DropReason::ClientBye);
      return;
    case Kind::KIND_NOT_SET:
      break;
  }
  session.close_with_error(physics::wire::ERROR_MALFORMED,
                           "ClientMessage holds no known message (empty or from a newer "
                           "protocol)",
                           DropReason::Malformed);
}

void Server::Impl::on_hello(Session& session, const physics::wire::Hello& hello) {
  if (session.joined()) {
    session.close_with_error(physics::wire::ERROR_UNEXPECTED_MESSAGE,
                             "a second Hello on the same connection",
                             DropReason::UnexpectedMessage);
    return;
  }
  const std::string name = printable_name(hello.client_name());
  if (hello.protocol_version() != wire::kProtocolVersion) {
    session.close_with_error(
        physics::wire::ERROR_PROTOCOL_VERSION,
        "client speaks protocol version " + std::to_string(hello.protocol_version()) +
            ", this server speaks version " + std::to_string(wire::kProtocolVersion),
        DropReason::ProtocolVersion);
    return;
  }
  if (config_.token && !same_token(hello.access_token(), *config_.token)) {
    session.close_with_error(physics::wire::ERROR_BAD_TOKEN,
                             hello.access_token().empty() ? "this server requires an access token"
                                                          : "wrong access token",
                             DropReason::BadToken);
    return;
  }
  wire::ViewSettings view;
  if (const std::string problem =
          wire::resolve_view(hello.view(), config_.max_snapshot_window, view);
      !problem.empty()) {
    session.close_with_error(physics::wire::ERROR_INVALID_VIEW, problem, DropReason::InvalidView);
    return;
  }
  if (hello.has_contacts()) {  // held from here; on_closed forgets it
    ContactFilter contacts;
    if (const std::string problem = resolve_contacts(hello.contacts(), hello.spectate(), contacts);
        !problem.empty()) {
      session.close_with_error(physics::wire::ERROR_INVALID_SUBSCRIPTION, problem,
                               DropReason::InvalidSubscription);
      return;
    }
    feeds_.subscribe_contacts(session.id(), std::move(contacts));
  }
  if (hello.spectate()) {
    join_spectator(session, name, view);
    return;
  }
  if (joined_count_ + lobby_.size() >= static_cast<std::size_t>(config_.max_clients)) {
    session.close_with_error(
        physics::wire::ERROR_SERVER_FULL,
        "server full: " + std::to_string(config_.max_clients) + " clients connected",
        DropReason::ServerFull);
    return;
  }
  const std::optional<std::uint32_t> wanted =
      hello.has_seat() ? std::optional<std::uint32_t>(hello.seat()) : std::nullopt;
  const SeatTable::Claim claim = seats_.claim(session.id(), wanted);
  switch (claim.outcome) {
    case SeatTable::Outcome::Seated:
      break;
    case SeatTable::Outcome::Taken:
      session.close_with_error(physics::wire::ERROR_SEAT_TAKEN,
                               "seat " + std::to_string(claim.seat) + " is taken",
                               DropReason::SeatTaken);
      return;
    case SeatTable::Outcome::OutOfRange:
      session.close_with_error(physics::wire::ERROR_SEAT_OUT_OF_RANGE,
                               "seat " + std::to_string(claim.seat) +
                                   " is out of range: seats are 0 to " +
                                   std::to_string(seats_.size() - 1),
                               DropReason::SeatOutOfRange);
      return;
    case SeatTable::Outcome::Full:
      session.close_with_error(
          physics::wire::ERROR_SERVER_FULL,
          "server full: all " + std::to_string(seats_.size()) + " seats are taken",
          DropReason::ServerFull);
      return;
  }
  if (!lobby_open_) {
    // The lobby: seated now, welcomed (with a body) once every seat is taken.
    session.set_joined(name);
    address_limits_.on_joined(session.address());
    lobby_.emplace(session.id(), LobbySeat{view});
    publish_connection_counts();
    spdlog::info("client {} '{}' ({}) seated in the lobby at seat {} ({} of {})", session.id(),
                 name, session.peer(), claim.seat, seats_.taken(), seats_.size());
    if (seats_.full()) open_lobby();
    return;
  }
  // Outside a lobby a seat moves the body only when the Hello asked for it, so that
  // clients that name no seat spawn as they always did.
  const std::optional<phys::BodyId> body = simulation_.join(session.id(), wanted);
  if (!body) {
    seats_.release(session.id());
    session.close_with_error(physics::wire::ERROR_NO_SPAWN,
                             "no free spawn position for another body", DropReason::NoSpawn);
    return;
  }
  session.set_joined(name);
  address_limits_.on_joined(session.address());
  welcome_player(session, *body, view);
}

void Server::Impl::welcome_player(Session& session, phys::BodyId body,
                                  const wire::ViewSettings& view) {
  feeds_.join(session.id(), view, body.packed());
  ++joined_count_;
  publish_connection_counts();
  const std::uint32_t seat = seats_.seat_of(session.id()).value_or(0);
  spdlog::info("client {} '{}' ({}) joined at tick {} in seat {} with body {}", session.id(),
               session.name(), session.peer(), simulation_.current_tick(), seat, body.packed());
  physics::wire::ServerMessage welcome =
      make_welcome(simulation_, session.id(), body, config_.lockstep, wire::to_wire(view),
                   static_cast<std::uint32_t>(config_.max_clients));
  welcome.mutable_welcome()->set_seat(seat);
  welcome.mutable_welcome()->set_seats(seats_.size());
  session.send(welcome);
}

// Every seat is taken: the bodies are made in seat order (each at its seat's spawn
// point when free), so that the world, body ids included, is the same whatever
// order the players connected in. Then every player is welcomed at tick 0.
void Server::Impl::open_lobby() {
  lobby_open_ = true;
  std::vector<std::pair<std::shared_ptr<Session>, phys::BodyId>> welcomed;
  for (const ClientId id : seats_.in_seat_order()) {
    const auto session = sessions_.find(id);
    if (session == sessions_.end() || lobby_.count(id) == 0) continue;
    const std::optional<phys::BodyId> body = simulation_.join(id, seats_.seat_of(id));
    if (!body) {
      lobby_.erase(id);
      seats_.release(id);
      session->second->close_with_error(physics::wire::ERROR_NO_SPAWN,
                                        "no free spawn position for another body",
                                        DropReason::NoSpawn);
      continue;
    }
    welcomed.emplace_back(session->second, *body);
  }
  std::map<std::uint32_t, LobbySeat> seated = std::move(lobby_);
  lobby_.clear();
  for (const auto& [session, body] : welcomed) {
    welcome_player(*session, body, seated.at(session->id()).view);
  }
  update_stats([](ServerStats& s) { s.lockstep_started = true; });
  spdlog::info("lobby full: {} players welcomed, tick 1 waits for their inputs", welcomed.size());
}

void Server::Impl::join_spectator(Session& session, const std::string& name,
                                  const wire::ViewSettings& view) {
  if (view.interest == wire::InterestKind::Radius) {
    session.close_with_error(physics::wire::ERROR_INVALID_VIEW,
                             "view.interest_radius needs a body to be around; a spectator may "
                             "use view.interest_rect",
                             DropReason::InvalidView);
    return;
  }
  if (spectator_count_ >= static_cast<std::size_t>(config_.max_spectators)) {
    session.close_with_error(
        physics::wire::ERROR_SERVER_FULL,
        "no room to watch: " + std::to_string(config_.max_spectators) + " spectators connected",
        DropReason::ServerFull);
    return;
  }
  session.set_joined(name);
  address_limits_.on_joined(session.address());
  spectators_.insert(session.id());
  feeds_.join(session.id(), view, std::nullopt);
  ++spectator_count_;
  publish_connection_counts();
  spdlog::info("spectator {} '{}' ({}) joined at tick {}", session.id(), name, session.peer(),
               simulation_.current_tick());
  physics::wire::ServerMessage welcome =
      make_welcome(simulation_, session.id(), phys::BodyId::invalid(), config_.lockstep,
                   wire::to_wire(view), static_cast<std::uint32_t>(config_.max_clients));
  welcome.mutable_welcome()->set_body_id(0);
  welcome.mutable_welcome()->set_spectator(true);
  session.send(welcome);
}

void Server::Impl::on_ack(Session& session, const physics::wire::Ack& ack) {
  if (feeds_.ack(session.id(), ack.tick()) == AckResult::Accepted) return;
  update_stats([](ServerStats& s) { ++s.invalid_acks; });
  session.send(wire::make_error(physics::wire::ERROR_INVALID_ACK,
                                "Ack for tick " + std::to_string(ack.tick()) +
                                    ", after the newest snapshot sent to this client; ignored",
                                false));
}

void Server::Impl::on_full_state_request(Session& session) {
  if (feeds_.request_full_state(session.id()) == FullStateResult::Accepted) return;
  update_stats([](ServerStats& s) { ++s.rate_limited; });
  session.send(wire::make_error(physics::wire::ERROR_RATE_LIMITED,
                                "a full state is already on its way to this client; the "
                                "request is merged with it",
                                false));
}

void Server::Impl::on_input(Session& session, const physics::wire::Input& input) {
  const InputCheck check =
      simulation_.submit_input(session.id(), input.tick(), {input.ax(), input.ay()});
  switch (check.verdict) {
    case InputVerdict::NonFinite:
      update_stats([](ServerStats& s) { ++s.invalid_inputs; });
      session.send(wire::make_error(physics::wire::ERROR_INVALID_INPUT,
                                    "input for tick " + std::to_string(input.tick()) +
                                        " has a NaN or infinite acceleration; dropped",
                                    false));
      return;
    case InputVerdict::TooFarAhead:
      update_stats([](ServerStats& s) { ++s.far_future_inputs; });
      session.send(wire::make_error(
          physics::wire::ERROR_TICK_TOO_FAR_AHEAD,
          "input for tick " + std::to_string(input.tick()) + " is more than " +
              std::to_string(simulation_.max_ticks_ahead()) + " ticks after the current tick " +
              std::to_string(simulation_.current_tick()) + "; dropped",
          false));
      return;
    case InputVerdict::NotJoined:
      return;  // cannot happen: on_message only passes inputs of joined sessions
    case InputVerdict::Late:
      update_stats([](ServerStats& s) { ++s.late_inputs; });
      break;
    case InputVerdict::OnTime:
      break;
  }
  if (check.clamped) {
    update_stats([](ServerStats& s) { ++s.clamped_inputs; });
    // Said once a player, not once an input: a client that always pushes past the
    // limit learns it without being sent an Error per tick.
    if (told_clamped_.insert(session.id()).second) {
      session.send(
          wire::make_error(physics::wire::ERROR_INPUT_CLAMPED,
                           "input for tick " + std::to_string(input.tick()) +
                               " is over the scene's max acceleration " +
                               std::to_string(simulation_.scene().max_acceleration) +
                               " m/s^2 (Welcome.max_acceleration) and was clamped to it; said once",
                           false));
    }
  }
  if (config_.lockstep) schedule_lockstep();
}

// ---- ticks ----

void Server::Impl::start_fixed_ticks() {
  phys::FixedTimestepConfig timestep_config;
  timestep_config.tick_rate_hz = simulation_.tick_rate();
  timestep_config.max_steps_per_frame =
      config_.steps_per_frame > 0 ? config_.steps_per_frame : simulation_.scene().steps_per_frame;
  timestep_.emplace(clock_, timestep_config);
  next_tick_due_ = clock_.now() + timestep_->period();
  arm_tick_timer();
}

void Server::Impl::arm_tick_timer() {
  tick_timer_.expires_at(next_tick_due_);
  tick_timer_.async_wait([this](std::error_code ec) {
    if (ec || stopping_) return;
    guard_tick([this] { on_tick_timer(); });
  });
}

// A session's handler that throws closes that session alone (session.cpp); a tick
// that throws leaves the one world this server owns half stepped, and serving it on
// would send clients a state no replay reproduces. So the server says why and stops.
template <class Tick>
void Server::Impl::guard_tick(Tick&& tick) {
  try {
    tick();
  } catch (const std::exception& error) {
    spdlog::critical("tick {} failed: {}; shutting down", simulation_.current_tick() + 1,
                     error.what());
    update_stats([&](ServerStats& s) { s.tick_failure = error.what(); });
    begin_shutdown();
  }
}

void Server::Impl::on_tick_timer() {
  const phys::FrameResult frame = timestep_->frame([this](double) { run_one_tick(); });
  if (frame.dropped_steps > 0) {
    update_stats([&](ServerStats& s) { s.dropped_steps += frame.dropped_steps; });
    if (log_admits("dropped steps"))
      spdlog::warn("fell behind: {} step(s) dropped after tick {}", frame.dropped_steps,
                   simulation_.current_tick());
  }
  // The next wake-up is the previous one plus a period, never "now + period", so
  // the timer's own latency does not accumulate into drift.
  const auto period = timestep_->period();
  next_tick_due_ += period;
  const auto now = clock_.now();
  if (next_tick_due_ < now) {
    // Fell behind by whole periods (the driver already dropped that backlog): skip
    // them, keeping the phase, instead of firing once per missed period.
    const auto behind = now - next_tick_due_;
    next_tick_due_ += (behind / period + 1) * period;
  }
  arm_tick_timer();
}

void Server::Impl::schedule_lockstep() {
  // Inputs arrive many to a read; checking the gate in a posted handler, at most
  // one pending at a time, keeps stepping out of the read loop (see try_lockstep).
  if (lockstep_check_posted_ || stopping_) return;
  lockstep_check_posted_ = true;
  asio::post(io_, [this] {
    lockstep_check_posted_ = false;
    guard_tick([this] { try_lockstep(); });
  });
}

void Server::Impl::try_lockstep() {
  if (stopping_) return;
  const LockstepGate::Decision decision =
      gate_.decide(simulation_.all_inputs_present(), simulation_.any_input_present(), clock_.now());
  if (decision != LockstepGate::Decision::Wait) {
    if (config_.lockstep_pace == ServerConfig::Pace::Realtime) {
      const auto now = clock_.now();
      if (now < next_lockstep_due_) {
        lockstep_timer_.expires_at(next_lockstep_due_);
        lockstep_timer_.async_wait([this](std::error_code ec) {
          if (!ec) schedule_lockstep();
        });
        return;
      }
      // Drift-free while on time; after a stall, no burst to catch up.
      next_lockstep_due_ = std::max(next_lockstep_due_ + tick_period_, now);
    }
    const TickResult result = run_one_tick();
    gate_.stepped();
    const bool timed_out = decision == LockstepGate::Decision::StepAfterTimeout;
    if (timed_out) {
      update_stats([&](ServerStats& s) {
        ++s.lockstep_timeouts;
        s.reused_inputs += result.held_over.size();
      });
      std::string missing;
      for (const ClientId client : result.held_over) {
        missing += (missing.empty() ? "" : ", ") + std::to_string(client);
      }
      spdlog::warn(
          "lockstep tick {} stepped after the {} ms timeout without input from client(s) {}",
          result.tick, config_.lockstep_timeout.count(), missing);
    }
    drop_stragglers(result, timed_out);
    // One tick per handler: when clients sent many ticks ahead, the write
    // completions of this tick's snapshots (queued before this post) run before the
    // next tick, so the sessions' snapshot queues drain instead of dropping.
    schedule_lockstep();
    return;
  }
  if (const auto deadline = gate_.deadline()) {
    lockstep_timer_.expires_at(*deadline);
    lockstep_timer_.async_wait([this](std::error_code ec) {
      if (!ec) schedule_lockstep();
    });
  } else {
    lockstep_timer_.cancel();
  }
}

TickResult Server::Impl::run_one_tick() {
  const auto started = std::chrono::steady_clock::now();
  // Contact events cost the step nothing while nobody subscribes.
  simulation_.set_contact_events(feeds_.any_contact_subscriber());
  TickResult result = simulation_.step_tick();
  const BodyChanges changes = simulation_.take_changes();
  for (const phys::BodyId id : changes.added) feeds_.note_added(id.packed());
  for (const std::uint64_t id : changes.removed) feeds_.note_removed(id);
  TruthFrame frame = read_truth(simulation_.world(), result.tick, &previous_frame_);
  broadcast(frame);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const double period = std::chrono::duration<double>(tick_period_).count();
  const bool overran = seconds > period;
  // At most a few lines a second (counted when suppressed): a scene too heavy for
  // its tick rate overruns every tick.
  if (overran && log_admits("tick overrun")) {
    spdlog::warn("tick {} overran: {:.3f} ms for a {:.3f} ms period", result.tick, seconds * 1e3,
                 period * 1e3);
  }
  const FeedStats& feed = feeds_.stats();
  std::size_t input_bytes = 0;
  for (const auto& [id, session] : sessions_) {
    if (const ClientInputs* inputs = simulation_.inputs_of(id))
      input_bytes += inputs->memory_bytes();
  }
  update_stats([&](ServerStats& s) {
    s.input_buffer_bytes = input_bytes;
    ++s.ticks_stepped;
    s.current_tick = result.tick;
    s.last_state_hash = frame.state_hash;
    s.last_tick_seconds = seconds;
    s.total_tick_seconds += seconds;
    if (seconds > s.max_tick_seconds) s.max_tick_seconds = seconds;
    const auto bound =
        std::lower_bound(kTickSecondsBounds.begin(), kTickSecondsBounds.end(), seconds);
    ++s.tick_seconds_buckets[static_cast<std::size_t>(bound - kTickSecondsBounds.begin())];
    if (overran) ++s.tick_overruns;
    s.last_tick_at = started;
    s.skipped_snapshots = feed.skipped;
    s.snapshots_sent = feed.snapshots;
    s.snapshot_records = feed.records;
    s.full_states = feed.full_states;
    s.view_updates = feed.views_updated;
    s.views = feeds_.view_count();
    s.max_view_error = feed.max_position_error;
  });
  const std::uint64_t state_hash = frame.state_hash;
  previous_frame_ = std::move(frame);
  if (config_.on_tick) config_.on_tick(result.tick, state_hash);
  return result;
}

void Server::Impl::broadcast(const TruthFrame& frame) {
  std::vector<FeedOutput> outputs =
      feeds_.after_tick(frame, simulation_.world(), [this](FeedClient client) {
        const ClientInputs* inputs = simulation_.inputs_of(client);
        ClientFields fields;
        if (inputs != nullptr) {
          fields.last_applied_input_tick = inputs->last_applied_tick();
          fields.has_applied_input = inputs->has_applied();
        }
        return fields;
      });
  std::size_t peak = 0;
  for (FeedOutput& out : outputs) {
    const auto it = sessions_.find(out.client);
    if (it == sessions_.end()) continue;
    // Held by a copy: a session that turns out too slow closes, and leaves the map.
    const std::shared_ptr<Session> session = it->second;
    if (session->closing()) continue;
    session->send_snapshot(std::move(out.shared), std::move(out.tail));
    peak = std::max(peak, session->queued_snapshots());
  }
  update_stats(
      [&](ServerStats& s) { s.peak_queued_snapshots = std::max(s.peak_queued_snapshots, peak); });
}

// ---- housekeeping and shutdown ----

void Server::Impl::arm_housekeeping() {
  housekeeping_timer_.expires_after(kHousekeepingPeriod);
  housekeeping_timer_.async_wait([this](std::error_code ec) {
    if (ec) return;
    const auto now = std::chrono::steady_clock::now();
    std::vector<std::shared_ptr<Session>> all;
    all.reserve(sessions_.size());
    for (const auto& [id, session] : sessions_) all.push_back(session);
    for (const auto& session : all) session->check_deadlines(now);
    log_limiter_.flush(now, [](const std::string& cause, std::uint64_t count) {
      spdlog::info("{} log line(s) of cause '{}' suppressed in the last second", count, cause);
    });
    if (config_.stats_log_interval.count() > 0 && now >= next_stats_line_ && !stopping_) {
      if (next_stats_line_ != std::chrono::steady_clock::time_point{}) log_stats_line();
      next_stats_line_ = now + config_.stats_log_interval;
    }
    // While stopping, keep going only until every session has closed; then the
    // io_context runs out of work and run() returns.
    if (!stopping_ || !sessions_.empty()) arm_housekeeping();
  });
}

void Server::Impl::log_stats_line() {
  const ServerStats s = stats();
  const double mean_ms =
      s.ticks_stepped > 0 ? s.total_tick_seconds * 1e3 / static_cast<double>(s.ticks_stepped) : 0.0;
  spdlog::info(
      "stats: tick {}, {} players, {} in lobby, {} spectators, {} connections; tick mean {:.3f} "
      "ms, "
      "max {:.3f} ms, {} overruns, {} dropped steps; {} bytes in, {} out; {} lockstep timeouts; "
      "{} snapshots skipped; {} sessions dropped",
      s.current_tick, s.connected_clients, s.lobby_clients, s.spectators, s.open_connections,
      mean_ms, s.max_tick_seconds * 1e3, s.tick_overruns, s.dropped_steps, s.bytes_received,
      s.bytes_sent, s.lockstep_timeouts, s.skipped_snapshots, s.dropped_by_fault());
}

// A player whose input was missing at lockstep_max_timeouts timed-out ticks in a row
// leaves the world now (so that the next tick no longer waits for it) and is told
// why; its session closes once the Error is written.
void Server::Impl::drop_stragglers(const TickResult& result, bool timed_out) {
  for (const ClientId id : stragglers_.after_step(result.held_over, timed_out)) {
    const auto it = sessions_.find(id);
    if (it == sessions_.end()) continue;
    const std::shared_ptr<Session> session = it->second;
    if (simulation_.leave(id)) {
      feeds_.leave(id);
      --joined_count_;
      publish_connection_counts();
    }
    stragglers_.forget(id);
    spdlog::warn("client {} '{}' ({}) dropped: no input at {} lockstep timeouts in a row", id,
                 session->name(), session->peer(), stragglers_.limit());
    session->close_with_error(physics::wire::ERROR_LOCKSTEP_STRAGGLER,
                              "no input at " + std::to_string(stragglers_.limit()) +
                                  " consecutive lockstep timeouts (--lockstep-max-timeouts)",
                              DropReason::LockstepStraggler);
  }
}

void Server::Impl::begin_shutdown() {
  if (stopping_) return;
  stopping_ = true;
  update_stats([](ServerStats& s) { s.shutting_down = true; });
  if (agones_) agones_->shutdown();
  spdlog::info("shutting down: closing {} connection(s)", sessions_.size());
  std::error_code ignored;
  acceptor_.close(ignored);
  tick_timer_.cancel();
  lockstep_timer_.cancel();
  accept_retry_timer_.cancel();
  if (signals_) signals_->cancel(ignored);
  std::vector<std::shared_ptr<Session>> all;
  for (const auto& [id, session] : sessions_) all.push_back(session);
  for (const auto& session : all) {
    session->close_with_error(physics::wire::ERROR_SHUTTING_DOWN, "the server is shutting down",
                              DropReason::ShuttingDown);
  }
  // Make sure the housekeeping timer is running to enforce close_linger.
  if (!sessions_.empty()) arm_housekeeping();
}

// ---- the public face ----

Server::Server(ServerConfig config, scene::SceneDef scene)
    : impl_(std::make_shared<Impl>(std::move(config), std::move(scene))) {}
Server::~Server() = default;
std::uint16_t Server::port() const { return impl_->port(); }
void Server::run() { impl_->run(); }
void Server::stop() { impl_->stop(); }
ServerStats Server::stats() const { return impl_->stats(); }
std::uint16_t Server::metrics_port() const { return impl_->metrics_port(); }

}  // namespace server
