#pragma once
// The Agones SDK's local REST API (the sidecar at 127.0.0.1:AGONES_SDK_HTTP_PORT),
// spoken from a thread of its own so that a slow or absent sidecar never delays a
// tick: POST /ready once the server serves (retried until the sidecar answers, as
// it may start after us), POST /health every health_period, PUT /metadata/label
// for the players and capacity labels when they change, and POST /shutdown when the
// server stops. docs/DEPLOY.md.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "server/server.h"

namespace server {

struct AgonesSdkConfig {
  std::string host = "127.0.0.1";
  std::uint16_t port = 9358;
  std::chrono::milliseconds health_period{2000};
  std::size_t capacity = 0;  // players the server takes: the capacity label
};

class AgonesSdk {
 public:
  AgonesSdk(AgonesSdkConfig config, std::function<ServerStats()> stats);
  // Sends Shutdown if not sent yet, then stops the thread.
  ~AgonesSdk();
  AgonesSdk(const AgonesSdk&) = delete;
  AgonesSdk& operator=(const AgonesSdk&) = delete;

  // The server listens and steps: tell Agones (from the SDK's thread).
  void ready();
  // The server stops (SIGTERM, stop(), or the match ended): tell Agones once.
  void shutdown();

 private:
  void run();
  bool post(const char* path);
  void set_label(const std::string& key, const std::string& value);

  AgonesSdkConfig config_;
  std::function<ServerStats()> stats_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool ready_asked_ = false;
  bool shutdown_asked_ = false;
  std::thread thread_;
};

}  // namespace server
