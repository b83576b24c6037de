#include "server_cli_flags.h"

#include <asio/ip/address.hpp>
#include <chrono>
#include <cstdlib>
#include <system_error>

#include "scene/scene.h"
#include "server/token_source.h"
#include "ticket/key_file.h"

namespace server {

namespace {

std::string ip_address_check(const std::string& text) {
  std::error_code ec;
  (void)asio::ip::make_address(text, ec);
  return ec ? "not an IP address: " + text : std::string();
}

void add_listening_flags(CLI::App& app, ServerFlags& f) {
  // A program with a scene of its own (goal-rush-server) names it as the default.
  const std::string default_scene = f.scene_file.empty() ? "the built-in scene" : f.scene_file;
  app.add_option("--scene", f.scene_file,
                 "Scene file (.textproto, see docs/SCENES.md); default: " + default_scene)
      ->check(CLI::ExistingFile);
  app.add_option("--bind", f.config.bind, "Address to listen on (IPv4 or IPv6)")
      ->capture_default_str()
      ->check(ip_address_check, "IP address");
  app.add_option("--port", f.port,
                 "TCP port; 0 picks a free one (printed as 'listening on ADDRESS:PORT')")
      ->capture_default_str()
      ->check(CLI::Range(0, 65535));
  app.add_option("--ws-port", f.ws_port,
                 "WebSocket port beside the TCP one, on the --bind address: the same messages, "
                 "one per binary frame, the same limits (docs/PROTOCOL.md); 0 picks a free one "
                 "(printed as 'websocket on ADDRESS:PORT'); default: off")
      ->check(CLI::Range(0, 65535));
  app.add_option("--tick-rate", f.tick_rate,
                 "Ticks per second; default: the scene's tick rate (60 in the built-in scene)")
      ->check(CLI::Number)
      ->check(CLI::Range(scene::kMinTickRate, scene::kMaxTickRate));
}

void add_lockstep_flags(CLI::App& app, ServerFlags& f) {
  app.add_flag("--lockstep", f.config.lockstep,
               "Lockstep: step tick N only when every client sent its input for N "
               "(or --lockstep-timeout-ms passed); ticks do not advance on their own");
  app.add_option("--lockstep-timeout-ms", f.lockstep_timeout_ms,
                 "Lockstep: how long to wait for missing inputs before reusing each "
                 "missing client's last input")
      ->capture_default_str()
      ->check(CLI::Range(1, 3600000));
  app.add_option("--lockstep-players", f.config.lockstep_players,
                 "Lockstep lobby (implies --lockstep): N seats, and nobody is welcomed until "
                 "all N are taken; bodies are made in seat order (Hello.seat), so a run does "
                 "not depend on the order clients connect in")
      ->check(CLI::Range(1, 100000));
  app.add_option("--lockstep-pace", f.lockstep_pace,
                 "Lockstep: realtime steps a tick once its inputs are in and its time at "
                 "the tick rate has come, as a game runs; asap as soon as its inputs are "
                 "in (tests, batch runs: clients that send ahead run it past the tick rate)")
      ->capture_default_str()
      ->check(CLI::IsMember({"asap", "realtime"}));
  app.add_option("--lockstep-max-timeouts", f.config.lockstep_max_timeouts,
                 "Lockstep: drop a player whose input was missing at this many timed-out "
                 "ticks in a row (ERROR_LOCKSTEP_STRAGGLER); 0 never drops")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000000));
  app.add_flag("--shutdown-after-match", f.config.shutdown_after_match,
               "With --lockstep-players: stop once the match has begun and every player has "
               "left (on Agones, the game server is then shut down)");
}

// Who may come in, and how often a refused address may try again.
void add_admission_flags(CLI::App& app, ServerFlags& f) {
  app.add_option("--max-clients", f.config.max_clients,
                 "Most players at once; the next one is refused with ERROR_SERVER_FULL. The "
                 "scene may fit fewer: a player for whom no spawn position is free is refused "
                 "with ERROR_NO_SPAWN, so the limit is whichever is reached first (the "
                 "built-in scene fits 58 players)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  app.add_option("--max-players-per-address", f.config.max_players_per_address,
                 "Most players joined at once from one address (spectators apart); the next "
                 "is refused with ERROR_SERVER_FULL. The default lets a LAN party behind one "
                 "NAT address in, not one machine squatting every seat; 0: no cap")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  app.add_option("--seat-backoff-ms", f.seat_backoff_ms,
                 "After a player from an address is dropped for straggling or not reading, "
                 "that address may not take a seat (ERROR_RATE_LIMITED) for this long, "
                 "doubled at each further drop up to --hello-backoff-max-ms")
      ->capture_default_str()
      ->check(CLI::Range(0L, 86400000L));
  app.add_option("--max-spectators", f.config.max_spectators,
                 "Most spectators (clients that watch without a body) at once")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  app.add_option("--token", f.token,
                 "Access token clients must send in Hello (refused with ERROR_BAD_TOKEN). "
                 "Visible to every user of the machine in /proc/PID/cmdline: prefer "
                 "--token-file or the PHYSICS_TOKEN environment variable");
  app.add_option("--token-file", f.token_file,
                 "Read the access token from the first line of this file");
  app.add_option("--ticket-key-file", f.ticket_key_file,
                 "Admit only clients whose Hello carries a connect ticket sealed with the key "
                 "in this file (physics-ticket --new-key; docs/SERVER.md, \"Connect tickets\"), "
                 "one connection per player id; in a lockstep lobby a ticket's seat is held for "
                 "its player. Replaces the access token: with --token, --token-file or "
                 "PHYSICS_TOKEN as well, the server refuses to start")
      ->check(CLI::ExistingFile);
  app.add_option("--ticket-room", f.config.ticket_room,
                 "The room a ticket must name, when it names one (at most 64 bytes); "
                 "default: the scene's name");
  app.add_option("--failed-hellos-before-backoff", f.config.failed_hellos_before_backoff,
                 "After this many failed Hellos in a row from one address (bad token, "
                 "version, frame; no Hello in time), refuse it at accept for a while")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  app.add_option("--hello-backoff-ms", f.hello_backoff_ms,
                 "The first refusal after too many failed Hellos; doubled at each further one")
      ->capture_default_str()
      ->check(CLI::Range(0L, 86400000L));
  app.add_option("--hello-backoff-max-ms", f.hello_backoff_max_ms,
                 "The longest refusal after failed Hellos; a quiet this long forgives them")
      ->capture_default_str()
      ->check(CLI::Range(0L, 86400000L));
}

// What one connection may send, and how long it may keep the server waiting.
void add_limit_flags(CLI::App& app, ServerFlags& f) {
  app.add_option("--connects-per-second", f.config.connects_per_second,
                 "Connections one address may open a second (0: unlimited)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--connect-burst", f.config.connect_burst,
                 "Connections one address may open at once before --connects-per-second applies")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--peer-bytes-per-second", f.config.peer_bytes_per_second,
                 "Bytes a second the server reads from one connection (bursts of the same); "
                 "over it, reading pauses (0: unlimited)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e12));
  app.add_option("--peer-messages-per-second", f.config.peer_messages_per_second,
                 "Messages a second the server handles from one connection (bursts of the "
                 "same); over it, reading pauses (0: unlimited)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e9));
  app.add_option("--full-state-bytes-per-second", f.config.full_state_bytes_per_second,
                 "Bytes of full states a client may be sent a second (bursts of twice that); "
                 "a FullStateRequest over it is answered ERROR_RATE_LIMITED (0: unlimited)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e12));
  app.add_option("--max-message-bytes", f.config.max_message_bytes,
                 "Largest message a client may send; larger ones get ERROR_MESSAGE_TOO_LARGE "
                 "and the connection is closed")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{64}, std::size_t{1} << 30));
  app.add_option("--max-snapshot-window", f.config.max_snapshot_window,
                 "Largest window of unacknowledged snapshots a client may ask for; a client "
                 "whose window is full skips ticks instead of queueing them")
      ->capture_default_str()
      ->check(CLI::Range(1u, 256u));
  app.add_option("--handshake-timeout-ms", f.handshake_timeout_ms,
                 "Close a connection that has not completed its Hello within this long")
      ->capture_default_str()
      ->check(CLI::Range(1L, 3600000L));
  app.add_option("--max-pending", f.config.max_pending,
                 "Most connections that have not joined yet, at once (never counted against "
                 "--max-clients)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  app.add_option("--max-pending-per-address", f.config.max_pending_per_address,
                 "Most connections that have not joined yet from one address")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  app.add_option("--idle-timeout-ms", f.idle_timeout_ms,
                 "Drop a client that sends nothing for this long (clients without inputs "
                 "send Ping), and a joined client that acknowledges none of the snapshots "
                 "sent to it for this long, whatever else it sends: a client must read "
                 "to keep its place")
      ->capture_default_str()
      ->check(CLI::Range(1L, 86400000L));
  app.add_option("--max-ticks-ahead", f.config.max_ticks_ahead,
                 "Refuse inputs for ticks further ahead of the current tick than this")
      ->capture_default_str()
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1000000}));
}

// The operations endpoint, the recording and the log.
void add_operations_flags(CLI::App& app, ServerFlags& f) {
  app.add_option("--metrics-port", f.metrics_port,
                 "Serve GET /healthz, /readyz and /metrics (Prometheus) over HTTP on this "
                 "port, on the --metrics-bind address; 0 picks a free one (printed as "
                 "'metrics on ADDRESS:PORT'); default: off")
      ->check(CLI::Range(0, 65535));
  app.add_option("--metrics-bind", f.config.metrics_bind,
                 "Address of the --metrics-port endpoint: loopback unless told otherwise "
                 "(a private interface, never the internet); at most 32 connections, 4 per "
                 "address, 2 s for a request, 8 KiB of headers, 20 requests a second per "
                 "address")
      ->capture_default_str()
      ->check(ip_address_check, "IP address");
  app.add_option("--stats-interval-s", f.stats_interval_s,
                 "Log a line of statistics this often; 0: never")
      ->capture_default_str()
      ->check(CLI::Range(0L, 86400L));
  app.add_option("--record", f.config.record_path,
                 "Record every join, leave, input applied and tick hash to FILE, for "
                 "physics-sim --replay (docs/REPLAY.md)");
  app.add_option("--log-level", f.log_level, "trace, debug, info, warn, error, critical or off")
      ->capture_default_str()
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  app.add_option("--log-format", f.log_format,
                 "text, or json: one JSON object a line (time, level, logger, message)")
      ->capture_default_str()
      ->check(CLI::IsMember({"text", "json"}));
}

}  // namespace

void add_server_flags(CLI::App& app, ServerFlags& flags, bool offer_rules) {
  add_listening_flags(app, flags);
  if (offer_rules) {
    app.add_option("--rules", flags.rules_file,
                   "A game's rules: a shared library built with physics_add_game_rules "
                   "(server/rules_plugin.h), against this version of the package; default: "
                   "no rules (every player gets the scene's player body)");
  }
  add_lockstep_flags(app, flags);
  add_admission_flags(app, flags);
  add_limit_flags(app, flags);
  add_operations_flags(app, flags);
}

std::string finish_server_config(ServerFlags& flags) {
  ServerConfig& config = flags.config;
  config.port = static_cast<std::uint16_t>(flags.port);
  if (config.lockstep_players > 0) config.lockstep = true;
  config.lockstep_pace =
      flags.lockstep_pace == "realtime" ? ServerConfig::Pace::Realtime : ServerConfig::Pace::Asap;
  if (flags.metrics_port >= 0) config.metrics_port = static_cast<std::uint16_t>(flags.metrics_port);
  if (flags.ws_port >= 0) config.ws_port = static_cast<std::uint16_t>(flags.ws_port);
  config.stats_log_interval = std::chrono::seconds(flags.stats_interval_s);
  // On Agones the sidecar's REST port comes in the environment (docs/DEPLOY.md).
  if (const char* agones_port = std::getenv("AGONES_SDK_HTTP_PORT"); agones_port != nullptr) {
    char* end = nullptr;
    const long value = std::strtol(agones_port, &end, 10);
    if (end == agones_port || *end != '\0' || value < 1 || value > 65535) {
      return std::string("AGONES_SDK_HTTP_PORT is not a port in 1 to 65535: ") + agones_port;
    }
    config.agones_sdk_port = static_cast<std::uint16_t>(value);
  }
  config.tick_rate = flags.tick_rate;
  config.lockstep_timeout = std::chrono::milliseconds(flags.lockstep_timeout_ms);
  config.idle_timeout = std::chrono::milliseconds(flags.idle_timeout_ms);
  config.handshake_timeout = std::chrono::milliseconds(flags.handshake_timeout_ms);
  TokenSources token_sources;
  token_sources.flag = flags.token;
  token_sources.file = flags.token_file;
  token_sources.env = std::getenv("PHYSICS_TOKEN");
  const TokenChoice token_choice = choose_token(token_sources);
  if (!token_choice.error.empty()) return token_choice.error;
  config.token = token_choice.token;
  if (!flags.ticket_key_file.empty()) {
    if (config.token) {
      return "--ticket-key-file replaces the access token: drop --token, --token-file and "
             "PHYSICS_TOKEN, or the ticket key";
    }
    ticket::Key key{};
    if (std::string error = ticket::read_key_file(flags.ticket_key_file, key); !error.empty()) {
      return error;
    }
    config.ticket_key = key;
  } else if (!config.ticket_room.empty()) {
    return "--ticket-room needs --ticket-key-file";
  }
  if (config.ticket_room.size() > ticket::kMaxRoomBytes) {
    return "--ticket-room is at most " + std::to_string(ticket::kMaxRoomBytes) + " bytes";
  }
  config.hello_backoff = std::chrono::milliseconds(flags.hello_backoff_ms);
  config.hello_backoff_max = std::chrono::milliseconds(flags.hello_backoff_max_ms);
  config.seat_backoff = std::chrono::milliseconds(flags.seat_backoff_ms);
  config.peer_byte_burst = config.peer_bytes_per_second;
  config.peer_message_burst = config.peer_messages_per_second;
  config.handle_signals = true;
  return {};
}

}  // namespace server
