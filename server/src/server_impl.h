#pragma once
// The server's insides: the acceptor, the sessions, the tick loop (fixed-timestep
// timer, or the lockstep gate) and the statistics, all on one io_context thread.
// Only stop() and stats() are called from other threads: stop() posts to the
// io_context, stats() reads a copy under a mutex. Who may join, and how, is the
// Handshake's to decide (handshake.h); the members are defined in server*.cpp,
// one file per job (server.cpp lists them).
#include <asio.hpp>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>

#include "address_limits.h"
#include "agones_sdk.h"
#include "handshake.h"
#include "input_timing.h"
#include "log_limiter.h"
#include "ops_http.h"
#include "physics/clock.h"
#include "physics/fixed_timestep.h"
#include "server/lockstep_gate.h"
#include "server/relay_log.h"
#include "server/server.h"
#include "server/simulation.h"
#include "session.h"
#include "snapshot_feeds.h"
#include "stragglers.h"
#include "truth_frame.h"
#include "wire/view_settings.h"
#include "ws_transport.h"

namespace server {

class Server::Impl final : public SessionHost {
 public:
  Impl(ServerConfig config, scene::SceneDef scene);
  ~Impl();

  std::uint16_t port() const { return port_; }
  std::uint16_t ws_port() const { return ws_port_; }
  std::uint16_t metrics_port() const { return metrics_ ? metrics_->port() : 0; }
  void run();
  void stop();
  ServerStats stats() const;

  // SessionHost
  void on_message(Session& session, physics::wire::ClientMessage& message) override;
  void on_closing(Session& session, DropReason reason) override;
  void on_closed(Session& session, DropReason reason) override;
  void on_bytes(std::size_t sent, std::size_t received) override;
  void on_throttled(Session& session) override;
  void on_handler_failed(Session& session, const char* what) override;

 private:
  void do_accept();
  void admit(asio::ip::tcp::socket socket, Transport transport);
  // The WebSocket port (ws_transport.cpp).
  void listen_ws(const asio::ip::address& address, std::uint16_t port);
  void do_ws_accept();
  void close_ws_acceptor();
  void refuse_if_too_many_pending(Session& fresh);
  // Refuses a connection at accept, without a session: one Error (on the WebSocket
  // port, an HTTP 429), written if the socket takes it at once, then closed.
  void refuse_at_accept(asio::ip::tcp::socket& socket, const std::string& text,
                        Transport transport);
  // Per-cause log limit (see log_limiter.h): false means the line is counted (with its
  // address), not written. Every line a stranger can cause goes through it.
  bool log_admits(const char* cause, const std::string& address = {});
  void start_fixed_ticks();
  void arm_tick_timer();
  void on_tick_timer();
  template <class Tick>
  void guard_tick(Tick&& tick);
  void schedule_lockstep();
  void try_lockstep();
  // The lockstep lobby (config.lockstep_players): bodies in seat order, then Welcomes.
  void open_lobby();
  void welcome_player(Session& session, phys::BodyId body, const wire::ViewSettings& view);
  void welcome_spectator(Session& session, const wire::ViewSettings& view);
  void drop_stragglers(const TickResult& result, bool timed_out);
  void log_stats_line();
  // `scheduled`: when the tick was due by the pace (input_timing.h).
  TickResult run_one_tick(std::optional<std::chrono::steady_clock::time_point> scheduled);
  void broadcast(const TruthFrame& frame);
  void arm_housekeeping();
  void drop_if_not_reading(Session& session, std::chrono::steady_clock::time_point now);
  void begin_shutdown();

  void on_hello(Session& session, const physics::wire::Hello& hello);
  void on_input(Session& session, const physics::wire::Input& input);
  void on_ack(Session& session, const physics::wire::Ack& ack);
  void on_full_state_request(Session& session);
  void on_game_message(Session& session, const physics::wire::GameMessage& message);
  // The game rules' messages of the tick (GameWorld::send, broadcast), after its
  // snapshots.
  void send_game_messages();
  // Each relay client's place in it: the last tick it was sent, and the first change
  // its world does not hold yet.
  struct RelayCursor {
    std::uint64_t after_tick = 0;
    std::uint64_t first_change = 0;
    bool resync = false;  // a FullStateRequest: the world's state goes next
    RelayLog::Audience audience = RelayLog::Audience::Followers;  // Hello.run_rules
  };
  // With Hello.want_world: the world's state in the Welcome, and the client's place
  // in the relay when its view is ENCODING_INPUTS.
  void give_world(Session& session, const wire::ViewSettings& view,
                  physics::wire::ServerMessage& welcome);
  // A relay client's snapshot bytes: the ticks since the previous one, or the
  // world's state when asked for or when the relay no longer holds its ticks.
  std::string relay_bytes(RelayCursor& cursor, std::uint64_t tick, std::uint32_t hash_interval);
  // A relay client left: the relay is detached (and its log emptied) with the last.
  void forget_relay_client(ClientId client);

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
  std::optional<asio::ip::tcp::acceptor> ws_acceptor_;  // config.ws_port set
  std::uint16_t ws_port_ = 0;
  asio::steady_timer ws_accept_retry_timer_;

  phys::SteadyClock clock_;
  std::optional<phys::FixedTimestep> timestep_;
  std::chrono::steady_clock::time_point next_tick_due_;
  LockstepGate gate_;
  SnapshotFeeds feeds_;
  TruthFrame previous_frame_;
  // The input relay (relay_log.h): attached to the simulation while a welcomed client
  // follows it (give_world, forget_relay_client), so that a server without such
  // clients pays nothing for it.
  RelayLog relay_log_;
  std::map<std::uint32_t, RelayCursor> relay_cursors_;

  std::map<std::uint32_t, std::shared_ptr<Session>> sessions_;
  std::uint32_t next_client_id_ = 1;  // see client_ids.h
  AddressLimits address_limits_;
  LogLimiter log_limiter_;
  bool stopping_ = false;
  bool lockstep_check_posted_ = false;

  // Players (their bodies are the simulation's room), seats, the lockstep lobby and
  // spectators; the lockstep stragglers (stragglers.h).
  Handshake handshake_;
  StragglerWatch stragglers_;
  std::set<std::uint32_t> told_clamped_;  // players already told of a clamped input
  std::chrono::steady_clock::time_point next_lockstep_due_{};                // Pace::Realtime
  std::optional<std::chrono::steady_clock::time_point> last_lockstep_step_;  // Pace::Asap
  InputTiming input_timing_;
  std::chrono::steady_clock::duration tick_period_{};
  std::chrono::steady_clock::time_point next_stats_line_{};
  std::unique_ptr<OpsHttp> metrics_;
  std::unique_ptr<AgonesSdk> agones_;

  mutable std::mutex stats_mutex_;
  ServerStats stats_;
};

}  // namespace server
