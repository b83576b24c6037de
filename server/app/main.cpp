// physics-server: the authoritative physics server on the command line. Everything
// it does is in the physics_server library (server/server.h); this file turns flags
// into a ServerConfig, loads the scene, and reports.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <asio/ip/address.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>
#include <variant>

#include "scene/scene.h"
#include "server/log_format.h"
#include "server/server.h"
#include "server/token_source.h"

namespace {

// Exit codes: 0 clean shutdown, 1 the server failed while running or could not
// listen, 2 bad flags or a bad scene file.
constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"physics-server: an authoritative 2D physics server speaking Protobuf over TCP"};
  server::ServerConfig config;
  std::string scene_file;
  double tick_rate = 0.0;
  int lockstep_timeout_ms = 250;
  long idle_timeout_ms = 10000;
  long handshake_timeout_ms = 2000;
  std::string token;
  std::string token_file;
  long hello_backoff_ms = 1000;
  long hello_backoff_max_ms = 60000;
  long seat_backoff_ms = 2000;
  std::string log_level = "info";
  std::string log_format = "text";
  std::string lockstep_pace = "asap";
  int port = config.port;
  int metrics_port = -1;
  int ws_port = -1;
  long stats_interval_s = 60;

  const auto ip_address_check = [](const std::string& text) {
    std::error_code ec;
    (void)asio::ip::make_address(text, ec);
    return ec ? "not an IP address: " + text : std::string();
  };
  app.add_option("--scene", scene_file,
                 "Scene file (.textproto, see docs/SCENES.md); default: the built-in scene")
      ->check(CLI::ExistingFile);
  app.add_option("--bind", config.bind, "Address to listen on (IPv4 or IPv6)")
      ->capture_default_str()
      ->check(ip_address_check, "IP address");
  app.add_option("--port", port,
                 "TCP port; 0 picks a free one (printed as 'listening on ADDRESS:PORT')")
      ->capture_default_str()
      ->check(CLI::Range(0, 65535));
  app.add_option("--ws-port", ws_port,
                 "WebSocket port beside the TCP one, on the --bind address: the same messages, "
                 "one per binary frame, the same limits (docs/PROTOCOL.md); 0 picks a free one "
                 "(printed as 'websocket on ADDRESS:PORT'); default: off")
      ->check(CLI::Range(0, 65535));
  app.add_option("--tick-rate", tick_rate,
                 "Ticks per second; default: the scene's tick rate (60 in the built-in scene)")
      ->check(CLI::Number)
      ->check(CLI::Range(scene::kMinTickRate, scene::kMaxTickRate));
  app.add_flag("--lockstep", config.lockstep,
               "Lockstep: step tick N only when every client sent its input for N "
               "(or --lockstep-timeout-ms passed); ticks do not advance on their own");
  app.add_option("--lockstep-timeout-ms", lockstep_timeout_ms,
                 "Lockstep: how long to wait for missing inputs before reusing each "
                 "missing client's last input")
      ->capture_default_str()
      ->check(CLI::Range(1, 3600000));
  app.add_option("--lockstep-players", config.lockstep_players,
                 "Lockstep lobby (implies --lockstep): N seats, and nobody is welcomed until "
                 "all N are taken; bodies are made in seat order (Hello.seat), so a run does "
                 "not depend on the order clients connect in")
      ->check(CLI::Range(1, 100000));
  app.add_option("--lockstep-pace", lockstep_pace,
                 "Lockstep: asap steps a tick as soon as its inputs are in; realtime also "
                 "waits for its time at the tick rate")
      ->capture_default_str()
      ->check(CLI::IsMember({"asap", "realtime"}));
  app.add_option("--lockstep-max-timeouts", config.lockstep_max_timeouts,
                 "Lockstep: drop a player whose input was missing at this many timed-out "
                 "ticks in a row (ERROR_LOCKSTEP_STRAGGLER); 0 never drops")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000000));
  app.add_option("--metrics-port", metrics_port,
                 "Serve GET /healthz, /readyz and /metrics (Prometheus) over HTTP on this "
                 "port, on the --metrics-bind address; 0 picks a free one (printed as "
                 "'metrics on ADDRESS:PORT'); default: off")
      ->check(CLI::Range(0, 65535));
  app.add_option("--metrics-bind", config.metrics_bind,
                 "Address of the --metrics-port endpoint: loopback unless told otherwise "
                 "(a private interface, never the internet); at most 32 connections, 4 per "
                 "address, 2 s for a request, 8 KiB of headers, 20 requests a second per "
                 "address")
      ->capture_default_str()
      ->check(ip_address_check, "IP address");
  app.add_flag("--shutdown-after-match", config.shutdown_after_match,
               "With --lockstep-players: stop once the match has begun and every player has "
               "left (on Agones, the game server is then shut down)");
  app.add_option("--stats-interval-s", stats_interval_s,
                 "Log a line of statistics this often; 0: never")
      ->capture_default_str()
      ->check(CLI::Range(0L, 86400L));
  app.add_option("--max-clients", config.max_clients,
                 "Most players at once; the next one is refused with ERROR_SERVER_FULL. The "
                 "scene may fit fewer: a player for whom no spawn position is free is refused "
                 "with ERROR_NO_SPAWN, so the limit is whichever is reached first (the "
                 "built-in scene fits 58 players)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  app.add_option("--max-players-per-address", config.max_players_per_address,
                 "Most players joined at once from one address (spectators apart); the next "
                 "is refused with ERROR_SERVER_FULL. The default lets a LAN party behind one "
                 "NAT address in, not one machine squatting every seat; 0: no cap")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  app.add_option("--seat-backoff-ms", seat_backoff_ms,
                 "After a player from an address is dropped for straggling or not reading, "
                 "that address may not take a seat (ERROR_RATE_LIMITED) for this long, "
                 "doubled at each further drop up to --hello-backoff-max-ms")
      ->capture_default_str()
      ->check(CLI::Range(0L, 86400000L));
  app.add_option("--max-spectators", config.max_spectators,
                 "Most spectators (clients that watch without a body) at once")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  app.add_option("--token", token,
                 "Access token clients must send in Hello (refused with ERROR_BAD_TOKEN). "
                 "Visible to every user of the machine in /proc/PID/cmdline: prefer "
                 "--token-file or the PHYSICS_TOKEN environment variable");
  app.add_option("--token-file", token_file,
                 "Read the access token from the first line of this file");
  app.add_option("--failed-hellos-before-backoff", config.failed_hellos_before_backoff,
                 "After this many failed Hellos in a row from one address (bad token, "
                 "version, frame; no Hello in time), refuse it at accept for a while")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  app.add_option("--hello-backoff-ms", hello_backoff_ms,
                 "The first refusal after too many failed Hellos; doubled at each further one")
      ->capture_default_str()
      ->check(CLI::Range(0L, 86400000L));
  app.add_option("--hello-backoff-max-ms", hello_backoff_max_ms,
                 "The longest refusal after failed Hellos; a quiet this long forgives them")
      ->capture_default_str()
      ->check(CLI::Range(0L, 86400000L));
  app.add_option("--connects-per-second", config.connects_per_second,
                 "Connections one address may open a second (0: unlimited)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--connect-burst", config.connect_burst,
                 "Connections one address may open at once before --connects-per-second applies")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--peer-bytes-per-second", config.peer_bytes_per_second,
                 "Bytes a second the server reads from one connection (bursts of the same); "
                 "over it, reading pauses (0: unlimited)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e12));
  app.add_option("--peer-messages-per-second", config.peer_messages_per_second,
                 "Messages a second the server handles from one connection (bursts of the "
                 "same); over it, reading pauses (0: unlimited)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e9));
  app.add_option("--full-state-bytes-per-second", config.full_state_bytes_per_second,
                 "Bytes of full states a client may be sent a second (bursts of twice that); "
                 "a FullStateRequest over it is answered ERROR_RATE_LIMITED (0: unlimited)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e12));
  app.add_option("--max-message-bytes", config.max_message_bytes,
                 "Largest message a client may send; larger ones get ERROR_MESSAGE_TOO_LARGE "
                 "and the connection is closed")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{64}, std::size_t{1} << 30));
  app.add_option("--max-snapshot-window", config.max_snapshot_window,
                 "Largest window of unacknowledged snapshots a client may ask for; a client "
                 "whose window is full skips ticks instead of queueing them")
      ->capture_default_str()
      ->check(CLI::Range(1u, 256u));
  app.add_option("--handshake-timeout-ms", handshake_timeout_ms,
                 "Close a connection that has not completed its Hello within this long")
      ->capture_default_str()
      ->check(CLI::Range(1L, 3600000L));
  app.add_option("--max-pending", config.max_pending,
                 "Most connections that have not joined yet, at once (never counted against "
                 "--max-clients)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  app.add_option("--max-pending-per-address", config.max_pending_per_address,
                 "Most connections that have not joined yet from one address")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  app.add_option("--idle-timeout-ms", idle_timeout_ms,
                 "Drop a client that sends nothing for this long (clients without inputs "
                 "send Ping), and a joined client that acknowledges none of the snapshots "
                 "sent to it for this long, whatever else it sends: a client must read "
                 "to keep its place")
      ->capture_default_str()
      ->check(CLI::Range(1L, 86400000L));
  app.add_option("--max-ticks-ahead", config.max_ticks_ahead,
                 "Refuse inputs for ticks further ahead of the current tick than this")
      ->capture_default_str()
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1000000}));
  app.add_option("--record", config.record_path,
                 "Record every join, leave, input applied and tick hash to FILE, for "
                 "physics-sim --replay (docs/REPLAY.md)");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error, critical or off")
      ->capture_default_str()
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  app.add_option("--log-format", log_format,
                 "text, or json: one JSON object a line (time, level, logger, message)")
      ->capture_default_str()
      ->check(CLI::IsMember({"text", "json"}));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? 0 : kExitUsage;
  }

  // Logs go to stderr, so that stdout carries only the "listening on" line.
  server::use_stderr_log("physics-server",
                         log_format == "json" ? server::LogFormat::Json : server::LogFormat::Text);
  config.port = static_cast<std::uint16_t>(port);
  if (config.lockstep_players > 0) config.lockstep = true;
  config.lockstep_pace = lockstep_pace == "realtime" ? server::ServerConfig::Pace::Realtime
                                                     : server::ServerConfig::Pace::Asap;
  if (metrics_port >= 0) config.metrics_port = static_cast<std::uint16_t>(metrics_port);
  if (ws_port >= 0) config.ws_port = static_cast<std::uint16_t>(ws_port);
  config.stats_log_interval = std::chrono::seconds(stats_interval_s);
  // On Agones the sidecar's REST port comes in the environment (docs/DEPLOY.md).
  if (const char* agones_port = std::getenv("AGONES_SDK_HTTP_PORT"); agones_port != nullptr) {
    char* end = nullptr;
    const long value = std::strtol(agones_port, &end, 10);
    if (end == agones_port || *end != '\0' || value < 1 || value > 65535) {
      std::cerr << "physics-server: AGONES_SDK_HTTP_PORT is not a port in 1 to 65535: "
                << agones_port << "\n";
      return kExitUsage;
    }
    config.agones_sdk_port = static_cast<std::uint16_t>(value);
  }
  spdlog::set_level(spdlog::level::from_str(log_level));
  config.tick_rate = tick_rate;
  config.lockstep_timeout = std::chrono::milliseconds(lockstep_timeout_ms);
  config.idle_timeout = std::chrono::milliseconds(idle_timeout_ms);
  config.handshake_timeout = std::chrono::milliseconds(handshake_timeout_ms);
  server::TokenSources token_sources;
  token_sources.flag = token;
  token_sources.file = token_file;
  token_sources.env = std::getenv("PHYSICS_TOKEN");
  const server::TokenChoice token_choice = server::choose_token(token_sources);
  if (!token_choice.error.empty()) {
    std::cerr << "physics-server: " << token_choice.error << "\n";
    return kExitUsage;
  }
  config.token = token_choice.token;
  config.hello_backoff = std::chrono::milliseconds(hello_backoff_ms);
  config.hello_backoff_max = std::chrono::milliseconds(hello_backoff_max_ms);
  config.seat_backoff = std::chrono::milliseconds(seat_backoff_ms);
  config.peer_byte_burst = config.peer_bytes_per_second;
  config.peer_message_burst = config.peer_messages_per_second;
  config.handle_signals = true;

  scene::SceneDef scene;
  if (scene_file.empty()) {
    scene = scene::default_scene();
  } else {
    scene::SceneResult loaded = scene::load_scene_file(scene_file);
    if (const auto* error = std::get_if<scene::SceneError>(&loaded)) {
      std::cerr << "physics-server: bad scene: " << error->to_string() << "\n";
      return kExitUsage;
    }
    scene = std::get<scene::SceneDef>(std::move(loaded));
  }

  const double effective_tick_rate = tick_rate > 0.0 ? tick_rate : scene.tick_rate;
  try {
    server::Server server(config, std::move(scene));
    // Tests and scripts read this line to learn the port (--port 0).
    std::cout << "listening on " << config.bind << ":" << server.port() << std::endl;
    if (config.ws_port) {
      std::cout << "websocket on " << config.bind << ":" << server.ws_port() << std::endl;
    }
    if (config.metrics_port) {
      std::cout << "metrics on " << config.metrics_bind << ":" << server.metrics_port()
                << std::endl;
    }
    spdlog::info("serving{} at {} ticks/s, at most {} clients{}",
                 config.lockstep ? " in lockstep" : "", effective_tick_rate, config.max_clients,
                 config.token ? ", token required" : "");
    server.run();
    const server::ServerStats stats = server.stats();
    const auto count = [&](server::DropReason reason) {
      const auto it = stats.dropped.find(reason);
      return it == stats.dropped.end() ? std::uint64_t{0} : it->second;
    };
    spdlog::info(
        "stopped after {} ticks; {} bytes sent; {} sessions ended: {} said bye, {} closed at "
        "shutdown, {} dropped",
        stats.ticks_stepped, stats.bytes_sent, stats.dropped_total(),
        count(server::DropReason::ClientBye), count(server::DropReason::ShuttingDown),
        stats.dropped_by_fault());
    if (!stats.tick_failure.empty()) {
      std::cerr << "physics-server: a tick failed: " << stats.tick_failure << "\n";
      return kExitFailure;
    }
  } catch (const std::invalid_argument& error) {
    std::cerr << "physics-server: " << error.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& error) {
    std::cerr << "physics-server: " << error.what() << "\n";
    return kExitFailure;
  }
  return 0;
}
