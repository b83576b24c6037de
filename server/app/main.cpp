// physics-server: the authoritative physics server on the command line. Everything
// it does is in the physics_server library (server/server.h); this file turns flags
// into a ServerConfig, loads the scene, and reports.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <asio/ip/address.hpp>
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <variant>

#include "scene/scene.h"
#include "server/server.h"

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
  std::string log_level = "info";

  app.add_option("--scene", scene_file,
                 "Scene file (.textproto, see docs/SCENES.md); default: the built-in scene")
      ->check(CLI::ExistingFile);
  app.add_option("--bind", config.bind, "Address to listen on (IPv4 or IPv6)")
      ->capture_default_str()
      ->check(
          [](const std::string& text) {
            std::error_code ec;
            (void)asio::ip::make_address(text, ec);
            return ec ? "not an IP address: " + text : std::string();
          },
          "IP address");
  app.add_option("--port", config.port,
                 "TCP port; 0 picks a free one (printed as 'listening on ADDRESS:PORT')")
      ->capture_default_str();
  app.add_option("--tick-rate", tick_rate,
                 "Ticks per second; default: the scene's tick rate (60 in the built-in scene)")
      ->check(CLI::Range(0.001, 10000.0));
  app.add_flag("--lockstep", config.lockstep,
               "Lockstep: step tick N only when every client sent its input for N "
               "(or --lockstep-timeout-ms passed); ticks do not advance on their own");
  app.add_option("--lockstep-timeout-ms", lockstep_timeout_ms,
                 "Lockstep: how long to wait for missing inputs before reusing each "
                 "missing client's last input")
      ->capture_default_str()
      ->check(CLI::Range(1, 3600000));
  app.add_option("--max-clients", config.max_clients,
                 "Most clients at once; the next one is refused with ERROR_SERVER_FULL")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  app.add_option("--max-spectators", config.max_spectators,
                 "Most spectators (clients that watch without a body) at once")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  app.add_option("--token", token,
                 "Access token clients must send in Hello (refused with ERROR_BAD_TOKEN)");
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
                 "Drop a client that sends nothing, or reads nothing, for this long "
                 "(clients without inputs send Ping)")
      ->capture_default_str()
      ->check(CLI::Range(1L, 86400000L));
  app.add_option("--max-ticks-ahead", config.max_ticks_ahead,
                 "Refuse inputs for ticks further ahead of the current tick than this")
      ->capture_default_str()
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1000000}));
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error, critical or off")
      ->capture_default_str()
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? 0 : kExitUsage;
  }

  // Logs go to stderr, so that stdout carries only the "listening on" line.
  spdlog::set_default_logger(spdlog::stderr_color_mt("physics-server"));
  spdlog::set_level(spdlog::level::from_str(log_level));
  config.tick_rate = tick_rate;
  config.lockstep_timeout = std::chrono::milliseconds(lockstep_timeout_ms);
  config.idle_timeout = std::chrono::milliseconds(idle_timeout_ms);
  config.handshake_timeout = std::chrono::milliseconds(handshake_timeout_ms);
  if (!token.empty()) config.token = token;
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
    spdlog::info("serving{} at {} ticks/s, at most {} clients{}",
                 config.lockstep ? " in lockstep" : "", effective_tick_rate, config.max_clients,
                 config.token ? ", token required" : "");
    server.run();
    const server::ServerStats stats = server.stats();
    spdlog::info("stopped after {} ticks; {} bytes sent; {} clients dropped", stats.ticks_stepped,
                 stats.bytes_sent, stats.dropped_total());
  } catch (const std::invalid_argument& error) {
    std::cerr << "physics-server: " << error.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& error) {
    std::cerr << "physics-server: " << error.what() << "\n";
    return kExitFailure;
  }
  return 0;
}
