// Built by scripts/test-package.sh with the flags of `pkg-config --cflags --libs
// physics_server` alone: a server in-process and a client that joins it.
#include <chrono>
#include <iostream>

#include "physics_testing/testing.h"

int main() {
  physics_testing::InProcessServer server(scene::default_scene());
  client::Client player(server.client_config("pkg-config"));
  if (!player.connect(std::chrono::seconds(3))) {
    std::cerr << "cannot join: " << player.last_error().to_string() << "\n";
    return 1;
  }
  std::cout << "joined '" << player.welcome().scene_name << "' with body "
            << player.welcome().body_id << "\n";
  return 0;
}
