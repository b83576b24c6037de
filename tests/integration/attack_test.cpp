// Attacks from one machine, as the internet would try them, each while a real player
// joins and is served: a stranger on 127.0.0.2 (the per-address limits), the player
// on 127.0.0.1. Each test states the bound on what the attack may cost the server.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "harness.h"
#include "wire/framing.h"

namespace itest {
namespace {

namespace pb = physics::wire;

constexpr char kStranger[] = "127.0.0.2";

// The server's own limits, as a deployment would run them: test_config() turns the
// per-address ones off for the other suites, which all connect from 127.0.0.1.
server::ServerConfig attack_config() {
  server::ServerConfig config = test_config();
  const server::ServerConfig defaults;
  config.failed_hellos_before_backoff = defaults.failed_hellos_before_backoff;
  config.connects_per_second = defaults.connects_per_second;
  config.handshake_timeout = 500ms;
  return config;
}

// 10,000 wrong tokens from one address: a few are answered ERROR_BAD_TOKEN, then the
// address is refused at accept (ERROR_RATE_LIMITED, or a reset), at no cost of a
// session; the player with the right token joins meanwhile.
TEST(Attack, WrongTokensFromOneAddressAreAnsweredAFewTimesThenRefusedAtAccept) {
  server::ServerConfig config = attack_config();
  config.token = "the-right-token";
  RunningServer server(config, scene::default_scene());
  constexpr int kAttempts = 10000;
  int bad_token = 0;
  int rate_limited = 0;
  for (int i = 0; i < kAttempts; ++i) {
    RawPeer peer(server.port(), kStranger);
    if (!peer.connected()) continue;
    peer.send(hello_message("guess", "guess-" + std::to_string(i)));
    if (auto error = peer.receive_error(2s)) {
      if (error->code() == pb::ERROR_BAD_TOKEN) ++bad_token;
      if (error->code() == pb::ERROR_RATE_LIMITED) ++rate_limited;
    }
    if (i == kAttempts / 2) {
      EXPECT_EQ(check_server_serves(server), "") << "while the guessing goes on";
    }
  }
  const server::ServerStats stats = server.stats();
  // The backoff starts after 8 failures and doubles (1 s, 2 s, ...): the run takes a
  // few seconds, so a handful more are answered, never thousands.
  std::printf("%d answered ERROR_BAD_TOKEN, %d ERROR_RATE_LIMITED, %llu refused at accept\n",
              bad_token, rate_limited,
              static_cast<unsigned long long>(dropped(stats, server::DropReason::AddressLimited)));
  EXPECT_GE(bad_token, 8);
  EXPECT_LE(dropped(stats, server::DropReason::BadToken), 16u);
  EXPECT_GE(dropped(stats, server::DropReason::AddressLimited), kAttempts - 16u);
  EXPECT_GT(rate_limited, 0);
  client::Client player(server.client_config("player"));
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
}

// 127 connections from one address that never say Hello: at most
// max_pending_per_address are held, each until the handshake deadline; the rest are
// refused at once. The player's seat is never taken.
TEST(Attack, SilentConnectionsHoldNoSeat) {
  RunningServer server(attack_config(), scene::default_scene());
  std::vector<std::unique_ptr<RawPeer>> silent;
  for (int i = 0; i < 127; ++i)
    silent.push_back(std::make_unique<RawPeer>(server.port(), kStranger));
  EXPECT_EQ(check_server_serves(server), "");
  const server::ServerConfig defaults;
  EXPECT_TRUE(eventually(
      [&] {
        return server.stats().open_connections == 0 &&
               dropped(server.stats(), server::DropReason::HandshakeTimeout) <=
                   static_cast<std::uint64_t>(defaults.max_pending_per_address);
      },
      5s));
}

// 127 announced 1 MiB frames before Hello, each sent but for its last byte: refused
// at the prefix (4 KiB before Hello), so none makes the server hold more than that.
TEST(Attack, AnnouncedLargeFramesAreRefusedAtTheirPrefix) {
  server::ServerConfig config = attack_config();
  config.connects_per_second = 0.0;  // all 127 at once: the frame limit is the subject
  RunningServer server(config, scene::default_scene());
  std::string prefix;
  wire::append_varint_prefix((1u << 20) - 1, prefix);
  const std::string body(64 * 1024, 'x');
  std::vector<std::unique_ptr<RawPeer>> peers;
  for (int i = 0; i < 127; ++i) {
    peers.push_back(std::make_unique<RawPeer>(server.port(), kStranger));
    peers.back()->send_bytes(prefix + body);
  }
  EXPECT_EQ(check_server_serves(server), "");
  int too_large = 0;
  for (auto& peer : peers) {
    if (auto error = peer->receive_error(2s))
      too_large += error->code() == pb::ERROR_MESSAGE_TOO_LARGE;
  }
  // Each is refused as soon as its prefix arrives, so none stays pending long enough
  // to meet the pending cap: all 127 get the same answer.
  EXPECT_EQ(too_large, 127);
  EXPECT_TRUE(eventually(
      [&] { return dropped(server.stats(), server::DropReason::MessageTooLarge) == 127; }, 5s));
}

// 127 pre-Hello sockets that send one Ping every 8 s (a renewal of the idle timer,
// on a server that answered Pings before Hello): the first Ping is fatal.
TEST(Attack, PingsBeforeHelloKeepNothingAlive) {
  RunningServer server(attack_config(), scene::default_scene());
  pb::ClientMessage ping;
  ping.mutable_ping()->set_nonce(1);
  int unexpected = 0;
  int refused = 0;
  std::vector<std::unique_ptr<RawPeer>> peers;
  for (int i = 0; i < 127; ++i) {
    peers.push_back(std::make_unique<RawPeer>(server.port(), kStranger));
    peers.back()->send(ping);
  }
  for (auto& peer : peers) {
    if (auto error = peer->receive_error(2s)) {
      unexpected += error->code() == pb::ERROR_UNEXPECTED_MESSAGE;
      refused += error->code() == pb::ERROR_SERVER_FULL || error->code() == pb::ERROR_RATE_LIMITED;
    }
  }
  std::printf("pings before Hello: %d answered ERROR_UNEXPECTED_MESSAGE, %d refused at the cap\n",
              unexpected, refused);
  EXPECT_GT(unexpected, 0);
  EXPECT_EQ(check_server_serves(server), "");
  EXPECT_TRUE(eventually([&] { return server.stats().open_connections == 0; }, 5s));
}

// One client sends a million inputs inside --max-ticks-ahead 1000000: the server
// holds one 32-byte slot a tick of their span (32 MB at most, stated in
// docs/SERVER.md) and gives it all back when the client goes.
TEST(Attack, AMillionInputsCostTheWindowAndComeBack) {
  constexpr std::uint64_t kInputs = 1000000;
  server::ServerConfig config = attack_config();
  config.max_ticks_ahead = kInputs;
  config.peer_messages_per_second = 0.0;  // the buffer's bound is the subject, not the rate
  config.peer_bytes_per_second = 0.0;
  RunningServer server(config, scene::default_scene());
  RawPeer attacker(server.port());
  ASSERT_TRUE(attacker.send(hello_message("hoarder")));
  std::optional<pb::ServerMessage> welcome;
  do {
    welcome = attacker.receive(3s);
  } while (welcome && !welcome->has_welcome());
  ASSERT_TRUE(welcome.has_value());
  const std::uint64_t from = welcome->welcome().current_tick() + 2;
  // Sent in chunks, so that the test holds little of it at once.
  constexpr std::uint64_t kChunk = 50000;
  for (std::uint64_t sent = 0; sent < kInputs; sent += kChunk) {
    std::string bytes;
    for (std::uint64_t i = sent; i < sent + kChunk; ++i) {
      // From the far end back: the order that would cost most if anything did.
      bytes += wire::encode_frame(input_message(from + kInputs - 1 - i - 1, 1.0, 0.0));
    }
    ASSERT_TRUE(attacker.send_bytes(bytes));
  }
  // Read in full once the buffer holds every tick still ahead of the server (the
  // ticks stepped meanwhile have taken theirs out). How long the reading takes
  // depends on the machine (a sanitizer build reads a few times slower), so the
  // wait ends only when the buffer has stopped growing for 10 s.
  const std::uint64_t last_tick = from + kInputs - 2;
  std::size_t peak = 0;
  bool read_in_full = false;
  auto grew_at = std::chrono::steady_clock::now();
  while (!read_in_full && std::chrono::steady_clock::now() - grew_at < 10s) {
    const server::ServerStats stats = server.stats();
    if (stats.input_buffer_bytes > peak) {
      peak = stats.input_buffer_bytes;
      grew_at = std::chrono::steady_clock::now();
    }
    const std::uint64_t ahead = last_tick > stats.current_tick ? last_tick - stats.current_tick : 0;
    read_in_full = stats.input_buffer_bytes / 32 + 2 >= ahead;
    std::this_thread::sleep_for(5ms);
  }
  EXPECT_TRUE(read_in_full) << "peak " << peak << " bytes";
  EXPECT_GE(peak, kInputs / 2 * 32);  // most of the million, one slot a tick
  EXPECT_LE(peak, (kInputs + 1) * 32);
  EXPECT_EQ(check_server_serves(server), "");
  attacker.close();
  EXPECT_TRUE(eventually([&] { return server.stats().connected_clients == 0; }, 5s));
  EXPECT_TRUE(eventually([&] { return server.stats().input_buffer_bytes == 0; }, 5s));
}

// A joined client that floods messages (acks, which need no reply) over its rate is
// slowed, not served at the others' cost: its reading pauses, counted, and the
// player is served at the tick rate meanwhile.
TEST(Attack, AFloodOfMessagesIsThrottled) {
  server::ServerConfig config = attack_config();
  config.peer_messages_per_second = 2000;
  config.peer_message_burst = 2000;
  RunningServer server(config, scene::default_scene());
  RawPeer flooder(server.port());
  ASSERT_TRUE(flooder.send(hello_message("flooder")));
  pb::ClientMessage ack;
  ack.mutable_ack()->set_tick(0);
  std::string flood;
  for (int i = 0; i < 6000; ++i) flood += wire::encode_frame(ack);
  ASSERT_TRUE(flooder.send_bytes(flood));
  EXPECT_TRUE(eventually([&] { return server.stats().throttled_reads > 0; }, 3s));
  EXPECT_EQ(check_server_serves(server), "");
  EXPECT_FALSE(flooder.closed());
}

// The other side of the rate limits: an honest client at 1 kHz, an input and an Ack
// every tick, with bursts of 200 Pings, is never paused for its rate nor dropped.
TEST(Attack, AnHonestClientAtOneKilohertzNeverMeetsTheRateLimits) {
  server::ServerConfig config = attack_config();
  config.tick_rate = 1000.0;
  RunningServer server(config, scene::default_scene());
  client::Client player(server.client_config("honest"));
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  std::uint64_t nonce = 0;
  std::size_t snapshots = 0;
  const auto until = std::chrono::steady_clock::now() + 2s;
  while (std::chrono::steady_clock::now() < until) {
    auto snapshot = player.next_snapshot(1s);  // taking it queues its Ack
    ASSERT_TRUE(snapshot.has_value()) << player.last_error().to_string();
    ++snapshots;
    ASSERT_TRUE(player.send_input(snapshot->tick + 1, 1.0, 0.0));
    if (snapshots % 250 == 0) {
      for (int i = 0; i < 200; ++i) ASSERT_TRUE(player.send_ping(++nonce));
    }
  }
  EXPECT_GT(snapshots, 0u);
  EXPECT_EQ(player.state(), client::ConnectionState::Connected);
  EXPECT_EQ(server.stats().throttled_reads, 0u);
  EXPECT_EQ(server.stats().dropped_total(), 0u);
}

// 60 peers join and leave while one client stops reading for 9.5 s (it keeps sending
// inputs, so it is not idle): what it is owed is bounded by the world, not by the
// churn, so it is neither dropped nor sent a frame larger than the world's full state
// when it reads again.
TEST(Attack, ChurnWhileAClientStallsNeitherDropsItNorBloatsItsFrames) {
  server::ServerConfig config = attack_config();
  // A client must acknowledge within the idle timeout to keep its place: the stall,
  // the probe and the read-back below take about 11 s.
  config.idle_timeout = 20s;
  RunningServer server(config, scene::default_scene());
  RawPeer stalled(server.port());
  stalled.set_receive_buffer(4096);
  ASSERT_TRUE(stalled.send(hello_message("stalled")));
  std::optional<pb::ServerMessage> welcome;
  do {
    welcome = stalled.receive(3s);
  } while (welcome && !welcome->has_welcome());
  ASSERT_TRUE(welcome.has_value());
  const std::size_t world_bytes = welcome->ByteSizeLong();
  const auto stall_ends = std::chrono::steady_clock::now() + 9500ms;
  int churned = 0;
  std::uint64_t tick = welcome->welcome().current_tick();
  while (std::chrono::steady_clock::now() < stall_ends) {
    if (churned < 60) {
      client::Client peer(server.client_config("churn-" + std::to_string(churned)));
      ASSERT_TRUE(peer.connect(3s)) << peer.last_error().to_string();
      peer.disconnect("churn");
      ++churned;
    }
    stalled.send(input_message(++tick, 0.0, 0.0));
    std::this_thread::sleep_for(150ms);
  }
  EXPECT_EQ(churned, 60);
  EXPECT_EQ(check_server_serves(server), "");
  // It reads again: every snapshot held for it, then new ones once it acknowledges.
  std::size_t largest = 0;
  std::uint64_t newest = 0;
  while (auto message = stalled.receive(500ms)) {
    ASSERT_FALSE(message->has_error()) << message->error().message();
    largest = std::max(largest, message->ByteSizeLong());
    if (message->has_snapshot()) newest = message->snapshot().tick();
  }
  ASSERT_GT(newest, 0u);
  pb::ClientMessage ack;
  ack.mutable_ack()->set_tick(newest);
  ASSERT_TRUE(stalled.send(ack));
  std::optional<pb::ServerMessage> after;
  do {
    after = stalled.receive(3s);
    ASSERT_TRUE(after.has_value()) << "no snapshot after the stall";
    ASSERT_FALSE(after->has_error()) << after->error().message();
    largest = std::max(largest, after->ByteSizeLong());
  } while (!after->has_snapshot() || after->snapshot().tick() <= newest);
  std::printf("largest frame to the stalled client: %zu bytes (the world's Welcome: %zu)\n",
              largest, world_bytes);
  EXPECT_LE(largest, 2 * world_bytes);
  EXPECT_EQ(dropped(server.stats(), server::DropReason::TooSlow), 0u);
}

}  // namespace
}  // namespace itest
