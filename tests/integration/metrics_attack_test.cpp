// Attacks on the operations endpoint (/healthz, /readyz, /metrics), each while a real
// player is served on the game port and a health probe from 127.0.0.1 must be
// answered: the strangers come from 127.0.0.2 and up (the per-address limits). Each
// test states the bound on what the attack may cost the server, from the endpoint's
// own counters (ServerStats::ops_http); the probes' latencies are printed, not
// asserted (they are measured, not tested).
#include <gtest/gtest.h>
#include <httplib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "harness.h"
#include "player_beside.h"

namespace itest {
namespace {

struct Probe {
  int answered = 0;
  int sent = 0;
  double worst_ms = 0.0;
};

// GET /healthz from 127.0.0.1, counted when answered 200 "ok".
void probe_health(RunningServer& server, Probe& probe) {
  httplib::Client http("127.0.0.1", server.get().metrics_port());
  http.set_connection_timeout(2s);
  http.set_read_timeout(2s);
  const auto start = std::chrono::steady_clock::now();
  const auto result = http.Get("/healthz");
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ++probe.sent;
  if (result && result->status == 200 && result->body == "ok\n") ++probe.answered;
  probe.worst_ms = std::max(probe.worst_ms, ms);
}

// The end of every attack: the player is still served and every probe was answered;
// prints the probes' figures and returns the endpoint's counters.
server::OpsHttpStats after_attack(const char* what, const RunningServer& server,
                                  const PlayerBeside& player, const Probe& probe) {
  EXPECT_TRUE(player.gets_snapshots()) << what;
  EXPECT_EQ(probe.answered, probe.sent) << what;
  std::printf("%s: %d of %d /healthz probes answered, the slowest in %.1f ms\n", what,
              probe.answered, probe.sent, probe.worst_ms);
  return server.stats().ops_http;
}

server::ServerConfig metrics_config() {
  server::ServerConfig config = test_config();
  config.metrics_port = 0;
  config.metrics_limits.request_deadline = 500ms;
  return config;
}

// The address of stranger i: 127.0.0.2, 127.0.0.3, ...
std::string stranger(int i) { return "127.0.0." + std::to_string(2 + i); }

long resident_kib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  }
  return -1;
}

// 4 sockets that send one header byte every 100 ms never finish a request: each is
// closed at its total deadline (not renewed by the bytes), and probes are answered.
TEST(MetricsAttack, SlowHeadersAreCutAtTheirDeadlineAndProbesAreAnswered) {
  RunningServer server(metrics_config(), scene::default_scene());
  PlayerBeside player(server);
  ASSERT_TRUE(player.joined()) << player.last_error();
  std::vector<std::unique_ptr<RawPeer>> slow;
  for (int i = 0; i < 4; ++i) {
    slow.push_back(std::make_unique<RawPeer>(server.get().metrics_port(), stranger(0)));
    slow.back()->send_bytes("GET /healthz HTTP/1.1\r\n");
  }
  Probe probe;
  for (int round = 0; round < 15; ++round) {
    for (auto& peer : slow) peer->send_bytes("X");
    probe_health(server, probe);
    std::this_thread::sleep_for(100ms);
  }
  const server::OpsHttpStats http = after_attack("slow headers", server, player, probe);
  std::printf("slow headers: %llu cut at the deadline\n",
              static_cast<unsigned long long>(http.deadline_expired));
  EXPECT_GE(http.deadline_expired, 4u);
  EXPECT_LE(http.peak_open_connections, 5u);  // the 4 slow ones and a probe
}

// 500 idle connections from 10 addresses: each address gets its burst of requests,
// then 429; at most max_connections are ever open, the oldest evicted for the newest;
// probes are answered all along.
TEST(MetricsAttack, IdleConnectionsNeverFillTheEndpoint) {
  RunningServer server(metrics_config(), scene::default_scene());
  PlayerBeside player(server);
  ASSERT_TRUE(player.joined()) << player.last_error();
  const server::OpsHttpLimits limits;
  // Plain sockets on one context: 500 RawPeers would hold 500 contexts' descriptors.
  asio::io_context context;
  std::vector<asio::ip::tcp::socket> idle;
  Probe probe;
  for (int i = 0; i < 500; ++i) {
    asio::ip::tcp::socket& socket = idle.emplace_back(context);
    std::error_code ec;
    socket.open(asio::ip::tcp::v4(), ec);
    if (!ec) socket.bind({asio::ip::make_address(stranger(i % 10)), 0}, ec);
    if (!ec) socket.connect({asio::ip::make_address("127.0.0.1"), server.get().metrics_port()}, ec);
    if (i % 100 == 99) probe_health(server, probe);
  }
  probe_health(server, probe);
  const server::OpsHttpStats http = after_attack("idle connections", server, player, probe);
  std::printf("idle connections: peak open %zu, %llu evicted, %llu refused 429\n",
              http.peak_open_connections, static_cast<unsigned long long>(http.evicted),
              static_cast<unsigned long long>(http.rate_limited));
  EXPECT_LE(http.peak_open_connections, static_cast<std::size_t>(limits.max_connections));
  EXPECT_GT(http.evicted, 0u);
  EXPECT_GT(http.rate_limited, 0u);
}

// 8 connections each sending a 16 MiB header line: each is answered 431 once it has
// sent max_header_bytes, and nothing more is held; the process's memory does not
// grow with the line.
TEST(MetricsAttack, AHugeHeaderIsRefusedAtTheCapAndNeverHeld) {
  RunningServer server(metrics_config(), scene::default_scene());
  PlayerBeside player(server);
  ASSERT_TRUE(player.joined()) << player.last_error();
  const server::OpsHttpLimits limits;
  const std::string chunk(64 * 1024, 'a');
  Probe probe;
  probe_health(server, probe);
  const long before_kib = resident_kib();
  std::size_t sent = 0;
  for (int i = 0; i < 8; ++i) {
    RawPeer peer(server.get().metrics_port(), stranger(i));
    peer.send_bytes("GET /metrics HTTP/1.1\r\nX-Huge: ");
    for (int k = 0; k < 256 && peer.send_bytes(chunk); ++k) sent += chunk.size();
    probe_health(server, probe);
  }
  const long after_kib = resident_kib();
  const server::OpsHttpStats http = after_attack("huge headers", server, player, probe);
  std::printf("huge headers: %zu bytes taken by the kernel; peak held %zu bytes; RSS %+ld KiB\n",
              sent, http.peak_held_header_bytes, after_kib - before_kib);
  EXPECT_EQ(http.header_too_large, 8u);
  // One connection at a time here: at most one cap's worth, plus a probe's request.
  EXPECT_LE(http.peak_held_header_bytes, limits.max_header_bytes + 1024);
}

// 200 requests as fast as one address can make them: past its burst they are refused
// 429 without a byte read; a probe from another address is not.
TEST(MetricsAttack, AFloodOfRequestsFromOneAddressIsRateLimited) {
  RunningServer server(metrics_config(), scene::default_scene());
  PlayerBeside player(server);
  ASSERT_TRUE(player.joined()) << player.last_error();
  Probe probe;
  for (int i = 0; i < 200; ++i) {
    RawPeer peer(server.get().metrics_port(), stranger(0));
    peer.send_bytes("GET /metrics HTTP/1.1\r\n\r\n");
    if (i % 50 == 0) probe_health(server, probe);
  }
  probe_health(server, probe);
  const server::OpsHttpStats http = after_attack("request flood", server, player, probe);
  std::printf("request flood: %llu refused 429\n",
              static_cast<unsigned long long>(http.rate_limited));
  // The burst (40) and what the rate refills while the loop runs are served.
  EXPECT_GE(http.rate_limited, 100u);
}

}  // namespace
}  // namespace itest
