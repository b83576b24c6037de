// /healthz, /readyz and /metrics over HTTP, scraped while a client plays, checked
// against what the test did.
#include <gtest/gtest.h>
#include <httplib.h>

#include <sstream>
#include <string>
#include <thread>

#include "harness.h"

namespace itest {
namespace {

// The value of the sample line `series VALUE`; "" if absent.
std::string sample(const std::string& text, const std::string& series) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind(series + ' ', 0) == 0) return line.substr(series.size() + 1);
  }
  return "";
}

TEST(MetricsEndpoint, ScrapesAgreeWithWhatTheClientDid) {
  server::ServerConfig config = test_config();
  config.metrics_port = 0;
  RunningServer server(config, scene::default_scene());
  ASSERT_NE(server.get().metrics_port(), 0);
  httplib::Client http("127.0.0.1", server.get().metrics_port());

  const auto health = http.Get("/healthz");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
  EXPECT_EQ(health->body, "ok\n");
  ASSERT_TRUE(eventually([&] { return server.stats().ticks_stepped > 0; }));
  const auto ready = http.Get("/readyz");
  ASSERT_TRUE(ready);
  EXPECT_EQ(ready->status, 200) << ready->body;

  {
    client::Client player(server.client_config("scraped"));
    ASSERT_TRUE(player.connect(3s));
    const std::uint64_t from = player.welcome().current_tick + 1;
    for (std::uint64_t tick = from; tick < from + 5; ++tick) player.send_input(tick, 1.0, 0.0);
    ASSERT_TRUE(player.wait_for_snapshot(
        3s, [&](const client::Snapshot& snapshot) { return snapshot.tick >= from + 5; }));
    const auto during = http.Get("/metrics");
    ASSERT_TRUE(during);
    EXPECT_EQ(sample(during->body, "physics_clients{state=\"playing\"}"), "1");
    player.disconnect();
  }
  ASSERT_TRUE(eventually([&] {
    const server::ServerStats s = server.stats();
    return dropped(s, server::DropReason::ClientBye) == 1 && s.open_connections == 0;
  }));
  const server::ServerStats after = server.stats();
  const auto metrics = http.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_EQ(metrics->status, 200);
  EXPECT_NE(metrics->get_header_value("Content-Type").find("text/plain"), std::string::npos);
  const std::string& text = metrics->body;
  EXPECT_EQ(sample(text, "physics_sessions_ended_total{reason=\"said_bye\"}"), "1");
  EXPECT_EQ(sample(text, "physics_clients{state=\"playing\"}"), "0");
  EXPECT_EQ(sample(text, "physics_connections_accepted_total"), "1");
  // Nothing arrives once the client has left: the count is settled.
  EXPECT_EQ(sample(text, "physics_bytes_received_total"), std::to_string(after.bytes_received));
  EXPECT_EQ(sample(text, "physics_clamped_inputs_total"), "0");
  const std::uint64_t ticks = std::stoull(sample(text, "physics_ticks_total"));
  EXPECT_GE(ticks, after.ticks_stepped);
  EXPECT_EQ(sample(text, "physics_tick_seconds_count"), std::to_string(ticks));
  EXPECT_EQ(sample(text, "physics_tick_seconds_bucket{le=\"+Inf\"}"), std::to_string(ticks));
  EXPECT_GT(std::stoull(sample(text, "physics_bytes_sent_total")), 0u);
  EXPECT_EQ(http.Get("/nothing-here")->status, 404);
}

TEST(MetricsEndpoint, ReadyzTurnsUnreadyOnceTheServerShutsDown) {
  server::ServerConfig config = test_config();
  config.metrics_port = 0;
  server::Server server(config, scene::default_scene());
  std::thread thread([&] { server.run(); });
  httplib::Client http("127.0.0.1", server.metrics_port());
  ASSERT_TRUE(eventually([&] { return server.stats().ticks_stepped > 0; }));
  EXPECT_EQ(http.Get("/readyz")->status, 200);
  server.stop();
  thread.join();
  const auto after = http.Get("/readyz");
  ASSERT_TRUE(after);
  EXPECT_EQ(after->status, 503);
  EXPECT_EQ(after->body, "shutting down\n");
  const auto metrics = http.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_EQ(sample(metrics->body, "physics_up"), "0");
}

}  // namespace
}  // namespace itest
