#include "physics_testing/in_process_server.h"

#include <stdexcept>
#include <utility>
#include <variant>

namespace physics_testing {

server::ServerConfig test_server_config(bool lockstep) {
  server::ServerConfig config;
  config.bind = "127.0.0.1";
  config.port = 0;
  config.lockstep = lockstep;
  // A test connects every client from 127.0.0.1, and may send bad Hellos on purpose:
  // the per-address defences against strangers would refuse it.
  config.failed_hellos_before_backoff = 1000000;
  config.connects_per_second = 0.0;
  config.max_players_per_address = 0;
  config.seat_backoff = std::chrono::milliseconds(0);
  // The server's info lines (every join and leave) would fill a test's output.
  config.log_level = server::LogLevel::Warn;
  return config;
}

Expected<scene::SceneDef> load_scene(const std::filesystem::path& file) {
  scene::SceneResult loaded = scene::load_scene_file(file);
  if (const auto* error = std::get_if<scene::SceneError>(&loaded)) {
    return Expected<scene::SceneDef>::failure(error->to_string());
  }
  return std::get<scene::SceneDef>(std::move(loaded));
}

namespace {

scene::SceneDef load_or_throw(const std::filesystem::path& file) {
  Expected<scene::SceneDef> scene = load_scene(file);
  if (!scene) throw std::runtime_error("cannot serve scene file: " + scene.message());
  return std::move(*scene);
}

}  // namespace

InProcessServer::InProcessServer(scene::SceneDef scene, server::ServerConfig config)
    : scene_(std::move(scene)),
      config_(std::move(config)),
      server_(config_, scene_),
      thread_([this] { server_.run(); }) {}

InProcessServer::InProcessServer(const std::filesystem::path& scene_file,
                                 server::ServerConfig config)
    : InProcessServer(load_or_throw(scene_file), std::move(config)) {}

InProcessServer::~InProcessServer() { stop(); }

void InProcessServer::stop() {
  server_.stop();
  if (thread_.joinable()) thread_.join();
}

Endpoint InProcessServer::endpoint() const {
  Endpoint endpoint;
  endpoint.host = connectable_host(config_.bind);
  endpoint.port = server_.port();
  endpoint.token = config_.token.value_or("");
  return endpoint;
}

}  // namespace physics_testing
