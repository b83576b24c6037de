#include "server/server_cli.h"

#include <spdlog/spdlog.h>

#include <exception>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <variant>

#include "server/log_format.h"
#include "server/rules_library.h"
#include "server/server.h"
#include "server_cli_flags.h"

namespace server {

namespace {

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

// The scene to serve, or nullopt after saying on stderr why it cannot be loaded.
std::optional<scene::SceneDef> load_scene(const ServerProgram& program, const std::string& file) {
  if (file.empty()) return scene::default_scene();
  scene::SceneResult loaded = scene::load_scene_file(file);
  if (const auto* error = std::get_if<scene::SceneError>(&loaded)) {
    std::cerr << program.name << ": bad scene: " << error->to_string() << "\n";
    return std::nullopt;
  }
  return std::get<scene::SceneDef>(std::move(loaded));
}

// The game's rules for `scene` (none without --rules or the program's own), or false
// after saying on stderr why they could not be made.
bool make_rules(const ServerProgram& program, const ServerFlags& flags,
                const scene::SceneDef& scene, std::shared_ptr<GameRules>& rules) {
  if (program.rules) {
    try {
      rules = program.rules(scene);
      return true;
    } catch (const std::exception& error) {
      std::cerr << program.name << ": the game's rules: " << error.what() << "\n";
      return false;
    }
  }
  if (flags.rules_file.empty()) return true;
  LoadedRules loaded = load_rules_library(flags.rules_file, scene);
  if (!loaded.rules) {
    std::cerr << program.name << ": " << loaded.error << "\n";
    return false;
  }
  rules = std::move(loaded.rules);
  return true;
}

void log_stop(const ServerStats& stats) {
  const auto count = [&](DropReason reason) {
    const auto it = stats.dropped.find(reason);
    return it == stats.dropped.end() ? std::uint64_t{0} : it->second;
  };
  spdlog::info(
      "stopped after {} ticks; {} bytes sent; {} sessions ended: {} said bye, {} closed at "
      "shutdown, {} dropped",
      stats.ticks_stepped, stats.bytes_sent, stats.dropped_total(), count(DropReason::ClientBye),
      count(DropReason::ShuttingDown), stats.dropped_by_fault());
}

int serve(const ServerProgram& program, const ServerConfig& config, scene::SceneDef scene) {
  const double tick_rate = config.tick_rate > 0.0 ? config.tick_rate : scene.tick_rate;
  try {
    Server server(config, std::move(scene));
    // Tests and scripts read this line to learn the port (--port 0).
    std::cout << "listening on " << config.bind << ":" << server.port() << std::endl;
    if (config.ws_port) {
      std::cout << "websocket on " << config.bind << ":" << server.ws_port() << std::endl;
    }
    if (config.metrics_port) {
      std::cout << "metrics on " << config.metrics_bind << ":" << server.metrics_port()
                << std::endl;
    }
    spdlog::info("serving{} at {} ticks/s, at most {} clients{}{}",
                 config.lockstep ? " in lockstep" : "", tick_rate, config.max_clients,
                 config.token ? ", token required" : "", config.rules ? ", with game rules" : "");
    server.run();
    const ServerStats stats = server.stats();
    log_stop(stats);
    if (!stats.tick_failure.empty()) {
      std::cerr << program.name << ": a tick failed: " << stats.tick_failure << "\n";
      return kExitFailure;
    }
  } catch (const std::invalid_argument& error) {
    std::cerr << program.name << ": " << error.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& error) {
    std::cerr << program.name << ": " << error.what() << "\n";
    return kExitFailure;
  }
  return 0;
}

}  // namespace

int run_server_cli(int argc, char** argv, const ServerProgram& program) {
  CLI::App app{program.description, program.name};
  ServerFlags flags;
  flags.port = flags.config.port;
  flags.scene_file = program.default_scene;
  add_server_flags(app, flags, !program.rules);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? 0 : kExitUsage;
  }
  // Logs go to stderr, so that stdout carries only the "listening on" line.
  use_stderr_log(program.name, flags.log_format == "json" ? LogFormat::Json : LogFormat::Text);
  if (const std::string error = finish_server_config(flags); !error.empty()) {
    std::cerr << program.name << ": " << error << "\n";
    return kExitUsage;
  }
  spdlog::set_level(spdlog::level::from_str(flags.log_level));

  std::optional<scene::SceneDef> scene = load_scene(program, flags.scene_file);
  if (!scene) return kExitUsage;
  if (!make_rules(program, flags, *scene, flags.config.rules)) return kExitUsage;
  return serve(program, flags.config, std::move(*scene));
}

}  // namespace server
