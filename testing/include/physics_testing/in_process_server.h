#pragma once
// A server::Server in the test's own process: it listens on a free loopback port
// (port 0) as soon as it is constructed, runs on its own thread, and is stopped and
// joined when the object goes away. Its stats() are the server's own counters.
#include <cstdint>
#include <filesystem>
#include <string>
#include <thread>

#include "physics_testing/endpoint.h"
#include "physics_testing/outcome.h"
#include "scene/scene.h"
#include "server/server.h"

namespace physics_testing {

// A config for tests: 127.0.0.1, port 0 (a free port), the given mode, no per-address
// connection rate or Hello backoff (every client of a test comes from one address),
// log lines of level warn and above only (set config.log_level to see more: Info
// shows every join and leave), otherwise the server's defaults.
server::ServerConfig test_server_config(bool lockstep = false);

// A scene file (docs/SCENES.md) as a SceneDef, or the loader's message (file, line
// and field).
Expected<scene::SceneDef> load_scene(const std::filesystem::path& file);

class InProcessServer {
 public:
  // Throws what server::Server throws: std::system_error when it cannot bind,
  // std::invalid_argument for a config that makes no sense.
  explicit InProcessServer(scene::SceneDef scene,
                           server::ServerConfig config = test_server_config());
  // The same from a scene file; std::runtime_error with the loader's message for a
  // file that does not load.
  explicit InProcessServer(const std::filesystem::path& scene_file,
                           server::ServerConfig config = test_server_config());
  ~InProcessServer();
  InProcessServer(const InProcessServer&) = delete;
  InProcessServer& operator=(const InProcessServer&) = delete;

  std::uint16_t port() const { return server_.port(); }
  Endpoint endpoint() const;
  client::ClientConfig client_config(const std::string& name = "test-client") const {
    return endpoint().client_config(name);
  }
  client::ClientConfig exact_client_config(const std::string& name = "test-client") const {
    return endpoint().exact_client_config(name);
  }
  server::ServerStats stats() const { return server_.stats(); }
  // The scene it serves, for an in-process reference run of the same world.
  const scene::SceneDef& scene() const { return scene_; }
  server::Server& server() { return server_; }
  // Stops the server and joins its thread (the destructor does it too). Idempotent.
  void stop();

 private:
  scene::SceneDef scene_;
  server::ServerConfig config_;
  server::Server server_;
  std::thread thread_;
};

}  // namespace physics_testing
