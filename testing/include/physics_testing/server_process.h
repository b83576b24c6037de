#pragma once
// physics-server as a child process, as a test in any language would run it: started
// with --port 0, its port read from the line it prints on stdout once listening
// ("listening on ADDRESS:PORT"), stopped with SIGTERM. Its stderr (the log) goes to a
// temporary file that log() reads; stdout after the handshake line is read and
// discarded, so that the child never blocks on a full pipe.
#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "physics_testing/endpoint.h"

namespace physics_testing {

struct ProcessOptions {
  // The physics-server executable: a path, or a name looked up in PATH. In CMake,
  // $<TARGET_FILE:physics::physics-server> gives the installed one.
  std::filesystem::path executable = "physics-server";
  // --scene; unset: the built-in default scene.
  std::optional<std::filesystem::path> scene_file;
  std::string bind = "127.0.0.1";
  // Further flags, e.g. {"--lockstep", "--tick-rate", "120"}. A "--token" given here
  // is also put into endpoint().token.
  std::vector<std::string> extra_args;
  // How long the server may take to print its listening line.
  std::chrono::milliseconds start_timeout{10000};
};

// The server's handshake line, "listening on ADDRESS:PORT" (IPv6 addresses appear
// bare, as in "listening on ::1:7777"): the endpoint it names, nullopt for any other
// line. The host is connectable_host(ADDRESS).
std::optional<Endpoint> parse_listening_line(std::string_view line);

class ServerProcess {
 public:
  // Starts the server and waits for its listening line. Throws std::runtime_error
  // when it cannot start, exits first (with its exit status and log), or prints no
  // such line within start_timeout (then it is killed).
  explicit ServerProcess(ProcessOptions options);
  // stop(), and removes the log file.
  ~ServerProcess();
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  const Endpoint& endpoint() const { return endpoint_; }
  std::uint16_t port() const { return endpoint_.port; }
  pid_t pid() const { return pid_; }
  client::ClientConfig client_config(const std::string& name = "test-client") const {
    return endpoint_.client_config(name);
  }
  client::ClientConfig exact_client_config(const std::string& name = "test-client") const {
    return endpoint_.exact_client_config(name);
  }

  // True while the child has not exited.
  bool running();
  // Sends SIGTERM and waits up to `timeout` for the child to exit, then SIGKILL.
  // Returns its exit code, or 128 + the signal that ended it (as a shell reports it).
  // Idempotent: later calls return the same status.
  int stop(std::chrono::milliseconds timeout = std::chrono::milliseconds(5000));
  // Everything the server has written to stderr so far.
  std::string log() const;

 private:
  void reap(int status);
  void kill_and_reap();

  ProcessOptions options_;
  std::filesystem::path log_path_;
  pid_t pid_ = -1;
  int stdout_fd_ = -1;
  std::optional<int> exit_status_;
  Endpoint endpoint_;
  std::thread drain_;
};

}  // namespace physics_testing
