#pragma once
// The authoritative physics server, in-process: construct it (it binds and listens
// at once, so port() is valid), call run() on a thread of your choice, and stop()
// from anywhere. physics-server (server/app/) is a thin command line around this.
// Design, threads, queues and limits: docs/SERVER.md.
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "scene/scene.h"
#include "server/game_rules.h"
#include "server/log_format.h"
#include "ticket/ticket.h"

namespace server {

// What the operations endpoint (/healthz, /readyz, /metrics) lets a stranger hold:
// docs/SERVER.md, "What a stranger can cost us".
struct OpsHttpLimits {
  // Connections open at once, in all and from one address. A new one over either
  // cap closes the oldest still reading its request (of that address, if it is the
  // address's cap), so a probe always gets in.
  int max_connections = 32;
  int max_connections_per_address = 4;
  // From accept to the end of the request's headers, whatever trickles in meanwhile;
  // then the connection is closed (408).
  std::chrono::milliseconds request_deadline{2000};
  // Request line and headers; over it: 431, then closed. Nothing more is ever held.
  std::size_t max_header_bytes = 8192;
  // Requests (one per connection) an address may make: this many a second, in
  // bursts of request_burst; over it: 429 at once, nothing read.
  double requests_per_second = 20.0;
  double request_burst = 40.0;
};

// What the operations endpoint holds and has refused (ServerStats::ops_http).
struct OpsHttpStats {
  std::size_t open_connections = 0;
  std::size_t peak_open_connections = 0;
  std::size_t held_header_bytes = 0;  // request bytes held now, all connections
  std::size_t peak_held_header_bytes = 0;
  std::uint64_t requests_answered = 0;  // any status, 429 and 431 included
  std::uint64_t evicted = 0;            // closed to make room for a newer connection
  std::uint64_t deadline_expired = 0;   // request not complete within request_deadline
  std::uint64_t header_too_large = 0;   // answered 431
  std::uint64_t malformed = 0;          // answered 400
  std::uint64_t rate_limited = 0;       // answered 429
};

struct ServerConfig {
  std::string bind = "127.0.0.1";
  // 0 picks a free port; port() tells which.
  std::uint16_t port = 7777;
  // The same protocol over WebSocket (one message per binary frame; docs/PROTOCOL.md),
  // on `bind` too, with the same limits and sessions: 0 picks a free port (ws_port()
  // tells which); unset: no WebSocket port.
  std::optional<std::uint16_t> ws_port;
  // Ticks per second; 0 takes the scene's tick rate.
  double tick_rate = 0.0;
  // At most this many ticks stepped per timer wake-up; 0 takes the scene's.
  int steps_per_frame = 0;
  // Lockstep: tick N is stepped only when every joined client has sent an input for
  // tick N, or lockstep_timeout has passed since the first input for tick N arrived
  // (then the missing clients' last inputs are reused, and counted). Ticks do not
  // advance while no client sends inputs, and are not paced by the wall clock.
  bool lockstep = false;
  std::chrono::milliseconds lockstep_timeout{250};
  // Lockstep lobby: with N > 0 there are N seats (instead of max_clients), and no
  // player is welcomed until all N are taken; then the bodies are made in seat order
  // and every player is welcomed at tick 0. Needs lockstep. docs/PROTOCOL.md, "Seats".
  int lockstep_players = 0;
  // Asap steps each tick as soon as its inputs are in; Realtime also waits for the
  // tick's time at the tick rate, as a game runs.
  enum class Pace : std::uint8_t { Asap, Realtime };
  Pace lockstep_pace = Pace::Asap;
  // A player whose input was missing at this many consecutive ticks stepped after a
  // timeout is dropped (ERROR_LOCKSTEP_STRAGGLER); 0 never drops.
  int lockstep_max_timeouts = 8;
  // Serve /healthz, /readyz and /metrics over HTTP on this port (0: a free one,
  // see Server::metrics_port()); unset: no HTTP endpoint. On metrics_bind, a
  // loopback address unless told otherwise: a scraper or an orchestrator's probe on
  // the same host, never the internet.
  std::optional<std::uint16_t> metrics_port;
  std::string metrics_bind = "127.0.0.1";
  OpsHttpLimits metrics_limits;
  // Log one line of statistics this often; 0: never.
  std::chrono::milliseconds stats_log_interval{0};
  // Speak the Agones SDK's local REST API at 127.0.0.1:this port (physics-server
  // takes it from AGONES_SDK_HTTP_PORT): Ready, Health every agones_health_period,
  // the players and capacity labels, Shutdown on stop. Unset: not on Agones.
  std::optional<std::uint16_t> agones_sdk_port;
  std::chrono::milliseconds agones_health_period{2000};
  // Lockstep lobby: once the match has begun and every player has left, stop (and,
  // on Agones, tell it to shut this game server down).
  bool shutdown_after_match = false;
  int max_clients = 64;
  // Players (not spectators) joined at once from one address; the next one is
  // refused ERROR_SERVER_FULL. 8 lets a household or a LAN party behind one NAT
  // address in, while holding every seat of the default 64 takes 8 addresses (and the
  // per-address pending and connect limits apply to each). 0: no cap (a tournament
  // behind one address with --token, say).
  int max_players_per_address = 8;
  // A player dropped for straggling in lockstep or for not reading may not take a
  // seat again from its address for seat_backoff, doubled at each further such drop
  // from that address (up to hello_backoff_max); meanwhile its Hellos are refused
  // ERROR_RATE_LIMITED. A quiet hello_backoff_max forgives the drops.
  std::chrono::milliseconds seat_backoff{2000};
  // Spectators (Hello.spectate) watch without a body and are counted apart from the
  // players: at most this many at once.
  int max_spectators = 16;
  // When set, a Hello without exactly this access token is refused.
  std::optional<std::string> token;
  // When set, a Hello must carry a connect ticket sealed with this key in its
  // access_token (docs/PROTOCOL.md, "Connect tickets"), for a player id that is not
  // connected already; a ticket's seat is held for its player in a lockstep lobby.
  // Tickets replace the token: setting both is refused with std::invalid_argument.
  std::optional<ticket::Key> ticket_key;
  // The room a ticket must name, when it names one; empty: the scene's name.
  std::string ticket_room;
  // A frame whose length prefix is over this is answered with an Error, then closed.
  std::size_t max_message_bytes = 1u << 20;
  // Before its Hello a connection may send frames of at most this many bytes (a
  // Hello is well under 1 KiB), so a stranger cannot make the server hold
  // max_message_bytes for each connection that never joins.
  std::size_t max_hello_bytes = 4096;
  // A connection must complete its Hello within this long (separately from the
  // idle timeout of joined clients); then it gets ERROR_TOO_SLOW and is closed.
  std::chrono::milliseconds handshake_timeout{2000};
  // Connections that have not joined yet: at most this many at once, and at most
  // max_pending_per_address from one address. They never count against max_clients.
  // When the pool is full, a new connection takes the place of the oldest pending
  // one, one that has sent nothing first (as a web server drops idle keep-alives
  // first): neither silent sockets nor ones that dribble bytes keep a would-be
  // player, whose Hello takes a round trip, out.
  int max_pending = 64;
  int max_pending_per_address = 8;
  // Per address: after failed_hellos_before_backoff failed Hellos in a row (bad
  // token, bad version, malformed, unexpected), it is refused at accept
  // (ERROR_RATE_LIMITED) for hello_backoff, doubled at each further failure up to
  // hello_backoff_max; a join clears the count, and so does a quiet
  // hello_backoff_max after the refusal ended. And it may open at most
  // connects_per_second connections a second (bursts of connect_burst).
  int failed_hellos_before_backoff = 8;
  std::chrono::milliseconds hello_backoff{1000};
  std::chrono::milliseconds hello_backoff_max{60000};
  double connects_per_second = 20.0;
  double connect_burst = 40.0;
  // What one connection may make us read and handle: bytes and messages a second,
  // with bursts. Over it, the server stops reading from it until the rate allows
  // (its bytes wait in the kernel's buffers, TCP slows the sender); it is not
  // dropped. An honest client (inputs and acks at 1 kHz, bursts of pings) stays
  // far below both. 0: unlimited.
  double peer_bytes_per_second = 1u << 20;
  double peer_byte_burst = 1u << 20;
  double peer_messages_per_second = 8192;
  double peer_message_burst = 8192;
  // Full states (the join's and those a client requests) are counted against a
  // budget per client: this many bytes a second, in bursts of twice that. A
  // FullStateRequest while the client is over its budget is answered
  // ERROR_RATE_LIMITED (not fatal) and dropped; the join's full state is always sent.
  // 64 KiB a second is two full states of a 1,000-body world (about 28 KB each).
  double full_state_bytes_per_second = 64 * 1024;
  // The largest window (snapshots sent and not yet acknowledged) a client may ask
  // for in Hello.view; the default window is min(12, this). A client whose window
  // is full skips ticks, so no client ever holds more than this many snapshots in
  // the server's queue and the kernel's buffers together.
  std::uint32_t max_snapshot_window = 64;
  // A client is dropped when nothing arrives from it for this long (clients that
  // send no inputs send Ping), when a write to it makes no progress this long, or,
  // once joined, when it has acknowledged none of the snapshots sent to it for this
  // long (whatever else it sends): a client must read to keep its place.
  std::chrono::milliseconds idle_timeout{10000};
  // An Input for a tick beyond current_tick + max_ticks_ahead is refused.
  std::uint64_t max_ticks_ahead = 120;
  // After a fatal Error (or on shutdown) a session gets this long to flush before
  // its socket is closed regardless.
  std::chrono::milliseconds close_linger{1000};
  // SO_SNDBUF of each client socket in bytes; 0 keeps the OS default (which grows
  // to megabytes). Smaller means a slow reader is noticed sooner and costs less
  // kernel memory; tests of slow clients use it.
  int socket_send_buffer_bytes = 0;
  // A client that has been sent nothing for this long (nothing in its view changed)
  // gets a snapshot of its header alone, so it knows the server still ticks.
  std::chrono::milliseconds heartbeat{1000};
  // Install SIGINT/SIGTERM handlers on the server's io_context (physics-server does).
  bool handle_signals = false;
  // Called on the server's thread after each tick is stepped and its snapshots are
  // queued, with the tick and the world's state hash (tests and embedders observe
  // runs with it; keep it short, it delays the next tick). If it throws, the tick
  // counts as failed: ServerStats::tick_failure says why and the server shuts down.
  std::function<void(std::uint64_t tick, std::uint64_t state_hash)> on_tick;
  // A game on the server (game_rules.h): called at fixed points of every tick, on
  // the server's thread. Unset: the world as the scene and the players make it.
  std::shared_ptr<GameRules> rules;
  // When set, every join, leave, input applied and tick hash is written to this file
  // (docs/REPLAY.md; physics-sim --replay steps it again). A file that cannot be
  // created is refused with std::invalid_argument.
  std::string record_path;
  // The least severe log line written: set, the server sets it when constructed
  // (server::set_log_level: spdlog's default logger, which is the process's); unset,
  // the level stays as it is (physics-server sets it from --log-level).
  // physics::testing's configs say Warn, so a test's output holds the server's
  // warnings and errors only.
  std::optional<LogLevel> log_level;
};

// Why sessions ended, as counted in ServerStats::dropped.
enum class DropReason : std::uint8_t {
  ClientBye,          // the client said Bye
  Disconnected,       // the peer closed or reset the connection
  MessageTooLarge,    // a length prefix over max_message_bytes
  Malformed,          // bytes that do not parse, or a bad varint prefix
  ProtocolVersion,    // Hello with another protocol version
  BadToken,           // missing or wrong access token
  ServerFull,         // max_clients reached
  NoSpawn,            // no free spawn point for the client's body
  UnexpectedMessage,  // e.g. Input before Hello, a second Hello
  Idle,               // nothing received for idle_timeout
  TooSlow,            // a write made no progress for idle_timeout
  ShuttingDown,       // the server stopped
  InvalidView,        // Hello.view with a field out of range
  HandshakeTimeout,   // no Hello within handshake_timeout
  TooManyPending,     // too many connections that have not joined (in all, or from one address)
  AddressLimited,     // refused at accept: the address failed too many Hellos, or connects too fast
  InternalError,      // handling its message threw (e.g. bad_alloc); the server goes on
  SeatTaken,          // Hello.seat held by another player
  SeatOutOfRange,     // Hello.seat not below the number of seats
  LockstepStraggler,  // missed lockstep_max_timeouts timed-out ticks in a row
  InvalidSubscription,  // Hello.contacts not allowed as given
  AddressFull,          // max_players_per_address players already joined from its address
  SeatBackoff,          // its address may not take a seat yet (seat_backoff after a drop)
  NotReading,           // joined, and acknowledged no snapshot for idle_timeout
  RefusedByGame,        // the game rules refused the player (GameRules::on_join)
};
const char* to_string(DropReason reason);

// Upper bounds (seconds) of the tick-time histogram's buckets; one more bucket
// counts the ticks above the last bound.
inline constexpr std::array<double, 12> kTickSecondsBounds = {
    0.0000625, 0.000125, 0.00025, 0.0005, 0.001, 0.002, 0.004, 0.008, 0.016, 0.032, 0.064, 0.128};

struct ServerStats {
  std::size_t connected_clients = 0;  // sessions that completed Hello and hold a body
  std::size_t lobby_clients = 0;      // players seated in the lockstep lobby, not yet welcomed
  std::size_t spectators = 0;         // sessions that completed Hello to watch
  std::size_t open_connections = 0;   // every open socket, joined or not
  std::uint64_t ticks_stepped = 0;
  std::uint64_t current_tick = 0;  // the last tick stepped
  std::uint64_t late_inputs = 0;   // applied at the next tick instead
  std::uint64_t far_future_inputs = 0;
  std::uint64_t invalid_inputs = 0;  // NaN or infinite
  std::uint64_t clamped_inputs = 0;  // magnitude over the scene's max_acceleration
  std::uint64_t lockstep_timeouts = 0;
  std::uint64_t reused_inputs = 0;  // lockstep: a missing input replaced by the last
  std::uint64_t dropped_steps = 0;  // backlog the fixed-timestep driver threw away
  // Due snapshots not sent because the client's window was full (it skipped them).
  std::uint64_t skipped_snapshots = 0;
  std::uint64_t snapshots_sent = 0;
  std::uint64_t snapshot_records = 0;  // body records in the snapshots sent
  std::uint64_t full_states = 0;       // full states sent (joins and requests)
  std::uint64_t relay_resyncs = 0;     // input-relay clients sent the world state again
  // Welcomed input-relay clients now; the relay is attached to the world only while > 0,
  // and holds this many stepped ticks (0 while detached).
  std::size_t relay_clients = 0;
  std::size_t relay_ticks_held = 0;
  std::uint64_t game_messages = 0;          // players' game messages accepted
  std::uint64_t game_messages_refused = 0;  // dropped with ERROR_INVALID_GAME_MESSAGE et al.
  std::uint64_t view_updates = 0;           // encodings made: one per view per due tick
  std::size_t views = 0;                    // views now (clients with equal views share one)
  std::uint64_t invalid_acks = 0;
  std::uint64_t rate_limited = 0;  // full-state requests while one was pending or over budget
  // Times a connection's reading was paused for being over its byte or message rate.
  std::uint64_t throttled_reads = 0;
  std::uint64_t failed_hellos = 0;         // Hellos refused (counted per address too)
  std::uint64_t suppressed_log_lines = 0;  // per-cause log limit: lines not written
  // Pending connections that had sent nothing, closed to make room for a newer one.
  std::uint64_t evicted_pending = 0;
  // Bytes the players' pending inputs hold now (ClientInputs::memory_bytes, summed).
  std::size_t input_buffer_bytes = 0;
  // The worst position error of any client's reconstruction against the world, over
  // every view update (per axis, metres): the tolerance bounds it, a byte budget may not.
  double max_view_error = 0.0;
  // The most snapshots one session ever held (the one being written included):
  // never above its window, however slow the client.
  std::size_t peak_queued_snapshots = 0;
  std::uint64_t bytes_sent = 0;
  std::uint64_t bytes_received = 0;
  std::uint64_t connections_accepted = 0;
  std::map<DropReason, std::uint64_t> dropped;  // sessions ended, by reason
  std::uint64_t last_state_hash = 0;
  // Wall time of the last tick's step plus snapshot encoding, and the largest seen.
  double last_tick_seconds = 0.0;
  double max_tick_seconds = 0.0;
  double total_tick_seconds = 0.0;  // over all ticks: mean = total / ticks_stepped
  // Ticks by their time: bucket i counts those in (bound[i-1], bound[i]].
  std::array<std::uint64_t, kTickSecondsBounds.size() + 1> tick_seconds_buckets{};
  std::uint64_t tick_overruns = 0;  // ticks whose step and encoding took longer than a period
  bool lockstep_started = false;    // lockstep: the lobby (if any) is full, ticks may step
  bool shutting_down = false;
  // Set when a tick threw (for example std::bad_alloc inside the step): the world may
  // be half stepped, so the server shuts down instead of serving it; the message says
  // why, and physics-server exits 1.
  std::string tick_failure;
  // When the last tick stepped (steady clock); for readiness.
  std::chrono::steady_clock::time_point last_tick_at{};
  // The operations endpoint's own counters (zero without config.metrics_port).
  OpsHttpStats ops_http;

  std::uint64_t dropped_total() const;
  // Sessions that ended for any reason but a Bye or the server's own shutdown.
  std::uint64_t dropped_by_fault() const;
};

class Server {
 public:
  // Builds the world from the scene and binds + listens. Throws std::system_error
  // (with the address in the message) if it cannot bind, std::invalid_argument for
  // a config that makes no sense (a tick rate outside [0.001, 1000], the range of
  // scene::tick_rate_problem; max_clients < 1, ...).
  Server(ServerConfig config, scene::SceneDef scene);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // The port actually listened on (the chosen one when config.port was 0).
  std::uint16_t port() const;
  // The WebSocket port listened on (0 without config.ws_port).
  std::uint16_t ws_port() const;
  // Serves until stop(); all sockets and the tick timer run on the calling thread.
  void run();
  // Thread-safe and idempotent. Sends ERROR_SHUTTING_DOWN to every client, closes
  // them (after at most close_linger) and makes run() return.
  void stop();
  // A consistent copy, safe from any thread.
  ServerStats stats() const;
  // The HTTP port of /healthz, /readyz and /metrics (0 without config.metrics_port).
  std::uint16_t metrics_port() const;

 private:
  class Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace server
