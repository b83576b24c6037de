// The Agones SDK's REST API as the server speaks it, against a small stand-in for
// the SDK server (the sidecar) started by the test: Ready once serving, Health
// periodically, the players and capacity labels, Shutdown on stop or at the end of
// a lobby's match.
#include <gtest/gtest.h>
#include <httplib.h>

#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "harness.h"

namespace itest {
namespace {

// Records every call; answers 200 with "{}" as the SDK server does, or 503 to the
// first `refuse_ready` Ready calls (a sidecar that is not up yet).
class SdkStandIn {
 public:
  explicit SdkStandIn(int refuse_ready = 0) : refuse_ready_(refuse_ready) {
    for (const char* path : {"/ready", "/health", "/shutdown"}) {
      http_.Post(path, [this, path](const httplib::Request&, httplib::Response& response) {
        std::lock_guard<std::mutex> lock(mutex_);
        calls_.push_back(std::string("POST ") + path);
        if (std::string(path) == "/ready" && refuse_ready_ > 0) {
          --refuse_ready_;
          response.status = 503;
          return;
        }
        response.set_content("{}", "application/json");
      });
    }
    http_.Put("/metadata/label",
              [this](const httplib::Request& request, httplib::Response& response) {
                std::lock_guard<std::mutex> lock(mutex_);
                calls_.push_back("PUT /metadata/label " + request.body);
                response.set_content("{}", "application/json");
              });
    port_ = http_.bind_to_any_port("127.0.0.1");
    thread_ = std::thread([this] { http_.listen_after_bind(); });
    while (!http_.is_running()) std::this_thread::yield();
  }
  ~SdkStandIn() {
    http_.stop();
    thread_.join();
  }
  std::uint16_t port() const { return static_cast<std::uint16_t>(port_); }
  std::vector<std::string> calls() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return calls_;
  }
  std::size_t count(const std::string& call) const {
    std::size_t n = 0;
    for (const auto& c : calls()) n += c == call ? 1 : 0;
    return n;
  }

 private:
  httplib::Server http_;
  int port_ = 0;
  std::thread thread_;
  mutable std::mutex mutex_;
  std::vector<std::string> calls_;
  int refuse_ready_;
};

const std::string kPlayersLabel = "PUT /metadata/label {\"key\":\"players\",\"value\":\"";

TEST(Agones, ReadyHealthAndLabelsWhileServingThenShutdownOnStop) {
  SdkStandIn sdk;
  server::ServerConfig config = test_config();
  config.agones_sdk_port = sdk.port();
  config.agones_health_period = 50ms;
  config.max_clients = 8;
  server::Server server(config, scene::default_scene());
  std::thread thread([&] { server.run(); });
  ASSERT_TRUE(eventually([&] { return sdk.count("POST /health") >= 2; }));
  EXPECT_EQ(sdk.calls().front(), "POST /ready");
  EXPECT_EQ(sdk.count("POST /ready"), 1u);
  EXPECT_EQ(sdk.count("PUT /metadata/label {\"key\":\"capacity\",\"value\":\"8\"}"), 1u);
  EXPECT_TRUE(eventually([&] { return sdk.count(kPlayersLabel + "0\"}") == 1; }));
  {
    client::ClientConfig cc;
    cc.port = server.port();
    client::Client player(cc);
    ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
    EXPECT_TRUE(eventually([&] { return sdk.count(kPlayersLabel + "1\"}") == 1; }));
  }
  EXPECT_EQ(sdk.count("POST /shutdown"), 0u);
  server.stop();
  thread.join();
  EXPECT_TRUE(eventually([&] { return sdk.count("POST /shutdown") == 1; }));
  EXPECT_EQ(sdk.calls().back(), "POST /shutdown");
}

TEST(Agones, ReadyIsRetriedUntilTheSdkServerTakesIt) {
  SdkStandIn sdk(/*refuse_ready=*/2);
  server::ServerConfig config = test_config();
  config.agones_sdk_port = sdk.port();
  config.agones_health_period = 50ms;
  server::Server server(config, scene::default_scene());
  std::thread thread([&] { server.run(); });
  ASSERT_TRUE(eventually([&] { return sdk.count("POST /health") >= 1; }));
  EXPECT_EQ(sdk.count("POST /ready"), 3u);  // two refused, the third taken
  const auto calls = sdk.calls();
  EXPECT_EQ(calls[0], "POST /ready");
  EXPECT_EQ(calls[1], "POST /ready");
  EXPECT_EQ(calls[2], "POST /ready");  // no health ping before Ready was taken
  server.stop();
  thread.join();
}

TEST(Agones, TheEndOfALobbyMatchStopsTheServerAndShutsTheGameServerDown) {
  SdkStandIn sdk;
  server::ServerConfig config = test_config(/*lockstep=*/true);
  config.lockstep_players = 1;
  config.shutdown_after_match = true;
  config.agones_sdk_port = sdk.port();
  config.agones_health_period = 50ms;
  server::Server server(config, scene::default_scene());
  std::thread thread([&] { server.run(); });
  {
    client::ClientConfig cc;
    cc.port = server.port();
    client::Client player(cc);
    ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
    ASSERT_TRUE(player.send_input(1, 0.0, 0.0));
    ASSERT_TRUE(player.next_snapshot(3s).has_value());
    player.disconnect("match over");
  }
  thread.join();  // run() returns by itself: nobody called stop()
  EXPECT_TRUE(server.stats().shutting_down);
  EXPECT_EQ(dropped(server.stats(), server::DropReason::ClientBye), 1u);
  EXPECT_TRUE(eventually([&] { return sdk.count("POST /shutdown") == 1; }));
}

}  // namespace
}  // namespace itest
