// Connections: accepting (and refusing at accept, by address), the caps on
// connections still handshaking, the log's per-cause limits, and a session's close.
#include <spdlog/spdlog.h>

#include <chrono>
#include <string>

#include "client_ids.h"
#include "handshake.h"
#include "log_fields.h"
#include "server_impl.h"
#include "wire/framing.h"
#include "wire/messages.h"

namespace server {

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
    admit(std::move(socket), Transport::Tcp);
    do_accept();
  });
}

// A connection accepted on either port: the same limits, ids and sessions.
void Server::Impl::admit(asio::ip::tcp::socket socket, Transport transport) {
  update_stats([](ServerStats& s) { ++s.connections_accepted; });
  std::error_code endpoint_error;
  const auto remote = socket.remote_endpoint(endpoint_error);
  if (!endpoint_error) {
    const std::string address = remote.address().to_string();
    const AddressLimits::Decision decision =
        address_limits_.on_accept(address, std::chrono::steady_clock::now());
    if (decision.verdict != AddressLimits::Verdict::Allowed) {
      const auto retry = std::chrono::ceil<std::chrono::milliseconds>(decision.retry_after).count();
      refuse_at_accept(socket,
                       decision.verdict == AddressLimits::Verdict::BackingOff
                           ? "too many failed Hellos from " + address + "; retry in " +
                                 std::to_string(retry) + " ms"
                           : "too many connections from " + address + "; retry in " +
                                 std::to_string(retry) + " ms",
                       transport);
      return;
    }
  }
  const std::uint32_t id = take_free_id(
      next_client_id_, [this](std::uint32_t live) { return sessions_.count(live) > 0; });
  auto session = std::make_shared<Session>(std::move(socket), id, *this, limits_,
                                           make_framing(transport, limits_));
  sessions_.emplace(id, session);
  publish_connection_counts();
  if (log_admits("connection", session->address())) {
    log_with(spdlog::level::info, {.client = id, .address = session->peer()},
             "connection {} from {}", id, session->peer());
  }
  session->start();
  refuse_if_too_many_pending(*session);
}

// Connections that have not joined have caps of their own, in all and per address,
// so that a stranger's sockets never take a player's seat (and each is closed at the
// handshake deadline anyway). Over a cap, the oldest pending connection (of the same
// address, for the address's cap) makes room for the newcomer, one that has sent
// nothing first: a would-be player sends its Hello at once and is through in a round
// trip, so the oldest is the one holding its place longest without a Hello, whether
// silent or dribbling bytes, and a real player always gets in.
void Server::Impl::refuse_if_too_many_pending(Session& fresh) {
  std::size_t pending = 0;
  std::size_t from_address = 0;
  // The oldest of the others: silent, and any, in all and from the newcomer's address.
  Session* oldest_silent = nullptr;
  Session* oldest_silent_here = nullptr;
  Session* oldest = nullptr;
  Session* oldest_here = nullptr;
  const auto older = [](Session* than, Session& session) {
    return than == nullptr || session.accepted_at() < than->accepted_at();
  };
  for (const auto& [id, session] : sessions_) {
    if (session->joined() || session->closing()) continue;
    ++pending;
    const bool here = session->address() == fresh.address();
    if (here) ++from_address;
    if (session.get() == &fresh) continue;
    if (older(oldest, *session)) oldest = session.get();
    if (here && older(oldest_here, *session)) oldest_here = session.get();
    if (session->has_sent_bytes()) continue;
    if (older(oldest_silent, *session)) oldest_silent = session.get();
    if (here && older(oldest_silent_here, *session)) oldest_silent_here = session.get();
  }
  const bool address_over =
      from_address > static_cast<std::size_t>(config_.max_pending_per_address);
  const bool all_over = pending > static_cast<std::size_t>(config_.max_pending);
  if (!address_over && !all_over) return;
  Session* victim = address_over ? (oldest_silent_here ? oldest_silent_here : oldest_here)
                                 : (oldest_silent ? oldest_silent : oldest);
  if (victim == nullptr) victim = &fresh;  // a cap of 0: nobody may wait
  update_stats([](ServerStats& s) { ++s.evicted_pending; });
  victim->close_with_error(physics::wire::ERROR_SERVER_FULL,
                           victim == &fresh
                               ? "no connection may wait to join here"
                               : "no Hello for too long while others wait to join: make room for a "
                                 "newer connection",
                           DropReason::TooManyPending);
}

void Server::Impl::refuse_at_accept(asio::ip::tcp::socket& socket, const std::string& text,
                                    Transport transport) {
  update_stats([](ServerStats& s) { ++s.dropped[DropReason::AddressLimited]; });
  if (log_admits("refused at accept")) {
    log_with(spdlog::level::info, {.reason = to_string(DropReason::AddressLimited)},
             "refused a connection: {}", text);
  }
  std::error_code ignored;
  socket.non_blocking(true, ignored);
  const std::string frame =
      transport == Transport::WebSocket
          ? ws_refusal_response(text)
          : wire::encode_frame(wire::make_error(physics::wire::ERROR_RATE_LIMITED, text, true));
  socket.write_some(asio::buffer(frame), ignored);
  socket.shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
  socket.close(ignored);
}

bool Server::Impl::log_admits(const char* cause, const std::string& address) {
  if (log_limiter_.admit(cause, std::chrono::steady_clock::now(), address)) return true;
  update_stats([](ServerStats& s) { ++s.suppressed_log_lines; });
  return false;
}

void Server::Impl::on_throttled(Session& session) {
  update_stats([](ServerStats& s) { ++s.throttled_reads; });
  if (log_admits("over its rate")) {
    log_with(spdlog::level::info, {.client = session.id(), .address = session.peer()},
             "connection {} ({}) is over its byte or message rate: reading paused", session.id(),
             session.peer());
  }
}

void Server::Impl::on_handler_failed(Session& session, const char* what) {
  if (log_admits("handler failed")) {
    log_with(spdlog::level::err,
             {.client = session.id(), .address = session.peer(), .reason = what},
             "handling a message of connection {} ({}) failed: {}; closing it", session.id(),
             session.peer(), what);
  }
}

// Settled when the end is decided, not when the socket closes: the peer sees the
// Error (and the end of the stream) before the server's close, and may take a seat
// again at once. It must find the back-off in force and a straggler's seat free.
void Server::Impl::on_closing(Session& session, DropReason reason) {
  if (!session.joined()) return;
  if (reason == DropReason::LockstepStraggler || reason == DropReason::NotReading ||
      reason == DropReason::TooSlow) {
    address_limits_.on_player_dropped(session.address(), std::chrono::steady_clock::now());
  }
  // A straggler has left the world (drop_stragglers); its seat goes with it.
  const std::uint32_t id = session.id();
  if (!simulation_.room().contains(id) && !handshake_.is_spectator(id) &&
      !handshake_.in_lobby(id)) {
    handshake_.leave(id);
  }
}

void Server::Impl::on_closed(Session& session, DropReason reason) {
  const std::uint32_t id = session.id();
  feeds_.leave(id);
  forget_relay_client(id);
  if (!session.joined() && is_failed_hello(reason)) {
    address_limits_.on_failed_hello(session.address(), std::chrono::steady_clock::now());
    update_stats([](ServerStats& s) { ++s.failed_hellos; });
  }
  // A seat freed already by on_closing leaves Member::None: a player all the same.
  const Handshake::Member member =
      session.joined() ? handshake_.leave(id) : Handshake::Member::None;  // frees its seat
  const LogFields left{.client = id, .address = session.peer(), .reason = to_string(reason)};
  const bool log_leave = session.joined() && log_admits("left", session.address());
  if (member == Handshake::Member::Spectator) {
    if (log_leave) {
      log_with(spdlog::level::info, left, "spectator {} '{}' ({}) left: {}", id, session.name(),
               session.peer(), to_string(reason));
    }
  } else if (member == Handshake::Member::Lobby) {
    if (log_leave) {
      log_with(spdlog::level::info, left, "client {} '{}' ({}) left the lobby: {}", id,
               session.name(), session.peer(), to_string(reason));
    }
  } else if (session.joined()) {
    // A straggler has left the world already (drop_stragglers).
    if (simulation_.leave(id)) feeds_.leave(id);
    input_timing_.forget(id);
    stragglers_.forget(id);
    told_clamped_.erase(id);
    if (log_leave) {
      log_with(spdlog::level::info, left, "client {} '{}' ({}) left: {}", id, session.name(),
               session.peer(), to_string(reason));
    }
  } else if (log_admits("closed before joining", session.address())) {
    log_with(spdlog::level::info, left, "connection {} ({}) closed before joining: {}", id,
             session.peer(), to_string(reason));
  }
  update_stats([&](ServerStats& s) { ++s.dropped[reason]; });
  sessions_.erase(id);
  publish_connection_counts();
  // One client fewer may be all the lockstep gate was waiting for. Posted, because
  // this can run in the middle of a broadcast.
  if (config_.lockstep) schedule_lockstep();
  if (config_.shutdown_after_match && config_.lockstep_players > 0 && handshake_.lobby_open() &&
      simulation_.room().size() == 0 && !stopping_) {
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
    s.connected_clients = simulation_.room().size();  // players welcomed and not gone
    s.lobby_clients = handshake_.lobby_size();
    s.spectators = handshake_.spectator_count();
    s.open_connections = sessions_.size();
  });
}

}  // namespace server
