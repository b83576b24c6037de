#pragma once
// The server's insides: the acceptor, the sessions, the tick loop (fixed-timestep
// timer, or the lockstep gate) and the statistics, all on one io_context thread.
// Only stop() and stats() are called from other threads: stop() posts to the
// io_context, stats() reads a copy under a mutex.
#include <asio.hpp>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>

#include "physics/clock.h"
#include "physics/fixed_timestep.h"
#include "server/lockstep_gate.h"
#include "server/server.h"
#include "server/simulation.h"
#include "session.h"
#include "snapshot_feeds.h"
#include "truth_frame.h"
#include "wire/view_settings.h"

namespace server {

class Server::Impl final : public SessionHost {
 public:
  Impl(ServerConfig config, scene::SceneDef scene);
  ~Impl();

  std::uint16_t port() const { return port_; }
  void run();
  void stop();
  ServerStats stats() const;

  // SessionHost
  void on_message(Session& session, physics::wire::ClientMessage& message) override;
  void on_closed(Session& session, DropReason reason) override;
  void on_bytes(std::size_t sent, std::size_t received) override;

 private:
  void do_accept();
  void refuse_if_too_many_pending(Session& fresh);
  void start_fixed_ticks();
  void arm_tick_timer();
  void on_tick_timer();
  void schedule_lockstep();
  void try_lockstep();
  TickResult run_one_tick();
  void broadcast(const TruthFrame& frame);
  void arm_housekeeping();
  void begin_shutdown();

  void on_hello(Session& session, const physics::wire::Hello& hello);
  void on_input(Session& session, const physics::wire::Input& input);
  void on_ack(Session& session, const physics::wire::Ack& ack);
  void join_spectator(Session& session, const std::string& name, const wire::ViewSettings& view);
  void on_full_state_request(Session& session);

  template <typename Update>
  void update_stats(Update&& update) {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    update(stats_);
  }
  void publish_connection_counts();

  // Declared first so that it is destroyed last: sockets and timers need it.
  asio::io_context io_;
  ServerConfig config_;
  Simulation simulation_;
  SessionLimits limits_;
  asio::ip::tcp::acceptor acceptor_;
  std::uint16_t port_ = 0;
  asio::steady_timer tick_timer_;
  asio::steady_timer lockstep_timer_;
  asio::steady_timer housekeeping_timer_;
  asio::steady_timer accept_retry_timer_;
  std::optional<asio::signal_set> signals_;

  phys::SteadyClock clock_;
  std::optional<phys::FixedTimestep> timestep_;
  std::chrono::steady_clock::time_point next_tick_due_;
  LockstepGate gate_;
  SnapshotFeeds feeds_;
  TruthFrame previous_frame_;

  std::map<std::uint32_t, std::shared_ptr<Session>> sessions_;
  std::size_t joined_count_ = 0;  // players
  std::size_t spectator_count_ = 0;
  std::set<std::uint32_t> spectators_;  // session ids
  std::uint32_t next_client_id_ = 1;
  bool stopping_ = false;
  bool lockstep_check_posted_ = false;

  mutable std::mutex stats_mutex_;
  ServerStats stats_;
};

}  // namespace server
