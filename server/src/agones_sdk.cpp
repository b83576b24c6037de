#include "agones_sdk.h"

#include <httplib.h>
#include <spdlog/spdlog.h>

#include <utility>

namespace server {
namespace {

// The sidecar is on the same host: anything slower than this is a sidecar in trouble,
// and the next health ping tries again.
constexpr auto kRequestTimeout = std::chrono::milliseconds(1000);
constexpr auto kReadyRetry = std::chrono::milliseconds(500);

}  // namespace

AgonesSdk::AgonesSdk(AgonesSdkConfig config, std::function<ServerStats()> stats)
    : config_(std::move(config)), stats_(std::move(stats)), thread_([this] { run(); }) {}

AgonesSdk::~AgonesSdk() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    shutdown_asked_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void AgonesSdk::ready() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ready_asked_ = true;
  }
  wake_.notify_all();
}

void AgonesSdk::shutdown() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    shutdown_asked_ = true;
  }
  wake_.notify_all();
}

bool AgonesSdk::post(const char* path) {
  httplib::Client http(config_.host, config_.port);
  http.set_connection_timeout(kRequestTimeout);
  http.set_read_timeout(kRequestTimeout);
  http.set_write_timeout(kRequestTimeout);
  // The gRPC gateway behind the REST API wants a JSON body, even an empty one.
  const auto response = http.Post(path, "{}", "application/json");
  if (!response || response->status != 200) {
    spdlog::warn("agones: POST {} failed: {}", path,
                 response ? "HTTP " + std::to_string(response->status)
                          : httplib::to_string(response.error()));
    return false;
  }
  return true;
}

void AgonesSdk::set_label(const std::string& key, const std::string& value) {
  httplib::Client http(config_.host, config_.port);
  http.set_connection_timeout(kRequestTimeout);
  http.set_read_timeout(kRequestTimeout);
  const std::string body = "{\"key\":\"" + key + "\",\"value\":\"" + value + "\"}";
  const auto response = http.Put("/metadata/label", body, "application/json");
  if (!response || response->status != 200) {
    spdlog::warn("agones: setting label {} failed", key);
  }
}

void AgonesSdk::run() {
  bool ready_sent = false;
  std::string players_label;
  std::unique_lock<std::mutex> lock(mutex_);
  const auto ready_due = [&] { return ready_asked_ && !ready_sent; };
  while (!shutdown_asked_) {
    if (ready_due()) {
      lock.unlock();
      ready_sent = post("/ready");
      if (ready_sent) {
        spdlog::info("agones: Ready sent to the SDK server on port {}", config_.port);
        set_label("capacity", std::to_string(config_.capacity));
      }
      lock.lock();
      if (!ready_sent) wake_.wait_for(lock, kReadyRetry, [this] { return shutdown_asked_; });
      continue;
    }
    // Woken early by ready() or shutdown(); otherwise a health ping is due.
    if (wake_.wait_for(lock, config_.health_period,
                       [&] { return shutdown_asked_ || ready_due(); })) {
      continue;
    }
    if (!ready_sent) continue;
    lock.unlock();
    post("/health");
    const ServerStats stats = stats_();
    const std::string players = std::to_string(stats.connected_clients + stats.lobby_clients);
    if (players != players_label) {
      set_label("players", players);
      players_label = players;
    }
    lock.lock();
  }
  lock.unlock();
  if (post("/shutdown")) spdlog::info("agones: Shutdown sent");
}

}  // namespace server
