// Housekeeping and shutdown: the periodic check of every session's deadlines, the
// suppressed-log counts and the stats line; closing every connection on stop.
#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>
#include <vector>

#include "log_fields.h"
#include "server_impl.h"

namespace server {
namespace {

constexpr auto kHousekeepingPeriod = std::chrono::milliseconds(100);

}  // namespace

void Server::Impl::arm_housekeeping() {
  housekeeping_timer_.expires_after(kHousekeepingPeriod);
  housekeeping_timer_.async_wait([this](std::error_code ec) {
    if (ec) return;
    const auto now = std::chrono::steady_clock::now();
    std::vector<std::shared_ptr<Session>> all;
    all.reserve(sessions_.size());
    for (const auto& [id, session] : sessions_) all.push_back(session);
    for (const auto& session : all) {
      session->check_deadlines(now);
      drop_if_not_reading(*session, now);
    }
    log_limiter_.flush(
        now, [](const std::string& cause, std::uint64_t count, std::size_t addresses) {
          spdlog::info(
              "{} more '{}' line(s) from {} address(es) in the last second, not logged one "
              "by one",
              count, cause, addresses);
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

// A joined client must read to keep its place: one that has acknowledged none of
// the snapshots outstanding for idle_timeout is dropped, whatever else it sends
// (Pings renew only the receive deadline).
void Server::Impl::drop_if_not_reading(Session& session,
                                       std::chrono::steady_clock::time_point now) {
  if (!session.joined() || session.closing() || !feeds_.has(session.id())) return;
  if (feeds_.unacknowledged(session.id()) == 0) {
    session.note_read_proof(now);
    return;
  }
  if (now - session.read_proof() < config_.idle_timeout) return;
  session.close_with_error(physics::wire::ERROR_TOO_SLOW,
                           "no snapshot acknowledged for " +
                               std::to_string(config_.idle_timeout.count()) +
                               " ms: a client must read (and Ack) to keep its place",
                           DropReason::NotReading);
}

void Server::Impl::log_stats_line() {
  const ServerStats s = stats();
  const double mean_ms =
      s.ticks_stepped > 0 ? s.total_tick_seconds * 1e3 / static_cast<double>(s.ticks_stepped) : 0.0;
  // "bytes": sent and received together; the prose has each.
  log_with(
      spdlog::level::info, {.tick = s.current_tick, .bytes = s.bytes_sent + s.bytes_received},
      "stats: tick {}, {} players, {} in lobby, {} spectators, {} connections; tick mean {:.3f} "
      "ms, "
      "max {:.3f} ms, {} overruns, {} dropped steps; {} bytes in, {} out; {} lockstep timeouts; "
      "{} snapshots skipped; {} sessions dropped",
      s.current_tick, s.connected_clients, s.lobby_clients, s.spectators, s.open_connections,
      mean_ms, s.max_tick_seconds * 1e3, s.tick_overruns, s.dropped_steps, s.bytes_received,
      s.bytes_sent, s.lockstep_timeouts, s.skipped_snapshots, s.dropped_by_fault());
}

void Server::Impl::begin_shutdown() {
  if (stopping_) return;
  stopping_ = true;
  update_stats([](ServerStats& s) { s.shutting_down = true; });
  if (agones_) agones_->shutdown();
  spdlog::info("shutting down: closing {} connection(s)", sessions_.size());
  std::error_code ignored;
  acceptor_.close(ignored);
  close_ws_acceptor();
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

}  // namespace server
