#include "physics_testing/server_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

extern char** environ;

namespace physics_testing {

namespace {

constexpr std::string_view kListeningPrefix = "listening on ";

std::string errno_text(const char* what, int error) {
  return std::string(what) + ": " + std::strerror(error);
}

std::string describe_status(int status) {
  if (WIFEXITED(status)) return "exited with code " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  return "ended with status " + std::to_string(status);
}

int shell_status(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return status;
}

// posix_spawn's file actions and attributes, released on every path out.
struct SpawnActions {
  posix_spawn_file_actions_t actions;
  SpawnActions() { posix_spawn_file_actions_init(&actions); }
  ~SpawnActions() { posix_spawn_file_actions_destroy(&actions); }
  SpawnActions(const SpawnActions&) = delete;
  SpawnActions& operator=(const SpawnActions&) = delete;
};

}  // namespace

std::optional<Endpoint> parse_listening_line(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (!line.starts_with(kListeningPrefix)) return std::nullopt;
  line.remove_prefix(kListeningPrefix.size());
  const std::size_t colon = line.rfind(':');
  if (colon == std::string_view::npos || colon == 0) return std::nullopt;
  const std::string_view address = line.substr(0, colon);
  const std::string_view digits = line.substr(colon + 1);
  unsigned port = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), port);
  if (error != std::errc{} || end != digits.data() + digits.size() || port == 0 || port > 65535) {
    return std::nullopt;
  }
  Endpoint endpoint;
  endpoint.host = connectable_host(address);
  endpoint.port = static_cast<std::uint16_t>(port);
  return endpoint;
}

// Long on purpose: spawning and reading the listening line share the descriptors and
// the cleanup each failure on the way needs, written once in the order they are made.
ServerProcess::ServerProcess(ProcessOptions options) : options_(std::move(options)) {
  std::vector<std::string> args = {options_.executable.string(), "--bind", options_.bind, "--port",
                                   "0"};
  if (options_.scene_file) {
    args.push_back("--scene");
    args.push_back(options_.scene_file->string());
  }
  args.insert(args.end(), options_.extra_args.begin(), options_.extra_args.end());
  const auto token = std::find(options_.extra_args.begin(), options_.extra_args.end(), "--token");
  if (token != options_.extra_args.end() && token + 1 != options_.extra_args.end()) {
    endpoint_.token = *(token + 1);
  }
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);

  std::string log_template =
      (std::filesystem::temp_directory_path() / "physics-server-XXXXXX.log").string();
  const int log_fd = mkostemps(log_template.data(), 4, O_CLOEXEC);
  if (log_fd < 0) throw std::runtime_error(errno_text("cannot create the server's log", errno));
  log_path_ = log_template;

  std::array<int, 2> pipe_fds{};
  if (pipe2(pipe_fds.data(), O_CLOEXEC) != 0) {
    const int error = errno;
    close(log_fd);
    throw std::runtime_error(errno_text("cannot make a pipe", error));
  }
  int spawned = 0;
  {
    SpawnActions spawn;
    posix_spawn_file_actions_addopen(&spawn.actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&spawn.actions, pipe_fds[1], 1);
    posix_spawn_file_actions_adddup2(&spawn.actions, log_fd, 2);
    // Nothing else of ours (listening sockets of in-process servers, other pipes)
    // leaks into the child.
    posix_spawn_file_actions_addclosefrom_np(&spawn.actions, 3);
    spawned = posix_spawnp(&pid_, argv[0], &spawn.actions, nullptr, argv.data(), environ);
  }
  close(pipe_fds[1]);
  close(log_fd);
  if (spawned != 0) {
    close(pipe_fds[0]);
    std::filesystem::remove(log_path_);
    pid_ = -1;
    throw std::runtime_error(errno_text(("cannot start " + args[0]).c_str(), spawned));
  }
  stdout_fd_ = pipe_fds[0];

  // Read stdout until the listening line, the end of the stream, or the deadline.
  const auto deadline = std::chrono::steady_clock::now() + options_.start_timeout;
  std::string pending;
  std::optional<std::string> failure;
  for (;;) {
    const std::size_t newline = pending.find('\n');
    if (newline != std::string::npos) {
      const std::string line = pending.substr(0, newline);
      pending.erase(0, newline + 1);
      if (auto found = parse_listening_line(line)) {
        found->token = endpoint_.token;
        endpoint_ = *found;
        break;
      }
      continue;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      failure = "printed no 'listening on ADDRESS:PORT' line within " +
                std::to_string(options_.start_timeout.count()) + " ms";
      break;
    }
    pollfd ready{stdout_fd_, POLLIN, 0};
    const int polled = poll(&ready, 1, static_cast<int>(left.count()));
    if (polled < 0 && errno == EINTR) continue;
    if (polled == 0) continue;
    std::array<char, 4096> buffer{};
    const ssize_t count = read(stdout_fd_, buffer.data(), buffer.size());
    if (count < 0 && errno == EINTR) continue;
    if (count <= 0) {
      int status = 0;
      waitpid(pid_, &status, 0);
      reap(status);
      failure = describe_status(status) + " before listening";
      break;
    }
    pending.append(buffer.data(), static_cast<std::size_t>(count));
  }
  if (failure) {
    kill_and_reap();
    const std::string log_text = log();
    close(stdout_fd_);
    stdout_fd_ = -1;
    std::filesystem::remove(log_path_);
    throw std::runtime_error(args[0] + " " + *failure + (log_text.empty() ? "" : "; its log:\n") +
                             log_text);
  }
  drain_ = std::thread([fd = stdout_fd_] {
    std::array<char, 4096> buffer{};
    for (;;) {
      const ssize_t count = read(fd, buffer.data(), buffer.size());
      if (count < 0 && errno == EINTR) continue;
      if (count <= 0) return;
    }
  });
}

ServerProcess::~ServerProcess() {
  stop();
  std::error_code ignored;
  std::filesystem::remove(log_path_, ignored);
}

void ServerProcess::reap(int status) {
  exit_status_ = shell_status(status);
  pid_ = -1;
}

void ServerProcess::kill_and_reap() {
  if (pid_ <= 0) return;
  kill(pid_, SIGKILL);
  int status = 0;
  while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  reap(status);
}

bool ServerProcess::running() {
  if (pid_ <= 0) return false;
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) == pid_) {
    reap(status);
    return false;
  }
  return true;
}

int ServerProcess::stop(std::chrono::milliseconds timeout) {
  if (pid_ > 0) {
    kill(pid_, SIGTERM);
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    // The child has no descriptor to wait on; poll its status with a short period.
    while (running() && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    kill_and_reap();
  }
  // The child is gone, so its stdout is at its end and the drain returns.
  if (drain_.joinable()) drain_.join();
  if (stdout_fd_ >= 0) {
    close(stdout_fd_);
    stdout_fd_ = -1;
  }
  return exit_status_.value_or(-1);
}

std::string ServerProcess::log() const {
  std::ifstream in(log_path_, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace physics_testing
