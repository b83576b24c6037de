// The real server on a loopback port, driven by raw sockets: the handshake, every
// refusal, slow and idle clients, lockstep, shutdown. Waits are bounded polls on
// what the server reports, never fixed sleeps.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <thread>

#include "server/server.h"
#include "server/simulation.h"
#include "socket_client.h"
#include "test_scene.h"
#include "wire/messages.h"

namespace {

using namespace std::chrono_literals;
using physics::wire::ServerMessage;
using server_test::SocketClient;

struct RunningServer {
  explicit RunningServer(server::ServerConfig config,
                         scene::SceneDef scene = server_test::free_space_scene())
      : server((config.port = 0, config), std::move(scene)), thread([this] { server.run(); }) {}
  ~RunningServer() {
    server.stop();
    thread.join();
  }
  std::uint16_t port() const { return server.port(); }
  server::Server server;
  std::thread thread;
};

template <typename Condition>
bool eventually(Condition condition, std::chrono::milliseconds timeout = 5000ms) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    if (condition()) return true;
    std::this_thread::sleep_for(5ms);
  }
  return condition();
}

// The next Error the client receives (skipping snapshots), if any.
std::optional<physics::wire::Error> next_error(SocketClient& client) {
  for (int i = 0; i < 1000; ++i) {
    const auto message = client.receive();
    if (!message) return std::nullopt;
    if (message->has_error()) return message->error();
  }
  return std::nullopt;
}

// The next snapshot, acknowledged (the server sends no more than a window of
// snapshots that were not).
std::optional<physics::wire::Snapshot> next_snapshot(SocketClient& client) {
  for (int i = 0; i < 1000; ++i) {
    const auto message = client.receive();
    if (!message) return std::nullopt;
    if (message->has_snapshot()) {
      physics::wire::ClientMessage ack;
      ack.mutable_ack()->set_tick(message->snapshot().tick());
      client.send(ack);
      return message->snapshot();
    }
  }
  return std::nullopt;
}

std::uint64_t drops(const server::Server& s, server::DropReason reason) {
  const auto stats = s.stats();
  const auto it = stats.dropped.find(reason);
  return it == stats.dropped.end() ? 0 : it->second;
}

TEST(ServerSocket, PortZeroPicksAFreePortAndABusyPortIsAClearError) {
  RunningServer running({});
  EXPECT_NE(running.port(), 0);
  server::ServerConfig same;
  same.port = running.port();
  try {
    server::Server second(same, server_test::free_space_scene());
    FAIL() << "a second server bound the same port";
  } catch (const std::system_error& error) {
    EXPECT_NE(std::string(error.what()).find(std::to_string(running.port())), std::string::npos)
        << error.what();
  }
}

TEST(ServerSocket, JoinGetsWelcomeThenSnapshotsInTickOrder) {
  RunningServer running({});
  SocketClient client(running.port());
  const auto welcome = client.join("alice");
  ASSERT_TRUE(welcome);
  EXPECT_EQ(welcome->client_id(), 1u);
  EXPECT_EQ(welcome->tick_rate(), 60.0);
  std::uint64_t previous = welcome->current_tick();
  bool saw_own_body = false;
  for (int i = 0; i < 10; ++i) {
    const auto snapshot = next_snapshot(client);
    ASSERT_TRUE(snapshot);
    EXPECT_GT(snapshot->tick(), previous);
    previous = snapshot->tick();
    for (const auto& body : snapshot->bodies())
      saw_own_body |= body.body_id() == welcome->body_id();
  }
  EXPECT_TRUE(saw_own_body);
  EXPECT_EQ(running.server.stats().connected_clients, 1u);
}

TEST(ServerSocket, WrongProtocolVersionIsRefusedNamingBothVersions) {
  RunningServer running({});
  SocketClient client(running.port());
  client.send(wire::make_hello("old", "", 7));
  const auto error = next_error(client);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->code(), physics::wire::ERROR_PROTOCOL_VERSION);
  EXPECT_TRUE(error->fatal());
  EXPECT_NE(error->message().find("7"), std::string::npos) << error->message();
  EXPECT_NE(error->message().find(std::to_string(wire::kProtocolVersion)), std::string::npos)
      << error->message();
  EXPECT_TRUE(client.wait_closed());
}

TEST(ServerSocket, TokenIsRequiredWhenConfigured) {
  // Value-initialized ({}): without it GCC 12 reports the assignment below as a read
  // of an uninitialized string (-Wmaybe-uninitialized, a false positive).
  server::ServerConfig config{};
  config.token = "s3cret";
  RunningServer running(config);
  SocketClient none(running.port());
  none.send(wire::make_hello("none"));
  auto error = next_error(none);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->code(), physics::wire::ERROR_BAD_TOKEN);
  EXPECT_TRUE(none.wait_closed());
  SocketClient wrong(running.port());
  wrong.send(wire::make_hello("wrong", "s3cres"));
  error = next_error(wrong);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->code(), physics::wire::ERROR_BAD_TOKEN);
  SocketClient right(running.port());
  EXPECT_TRUE(right.join("right", "s3cret"));
  EXPECT_TRUE(
      eventually([&] { return drops(running.server, server::DropReason::BadToken) == 2u; }));
}

TEST(ServerSocket, ClientPastMaxClientsIsRefused) {
  server::ServerConfig config;
  config.max_clients = 1;
  RunningServer running(config);
  SocketClient first(running.port());
  ASSERT_TRUE(first.join("first"));
  SocketClient second(running.port());
  second.send(wire::make_hello("second"));
  const auto error = next_error(second);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->code(), physics::wire::ERROR_SERVER_FULL);
  EXPECT_TRUE(second.wait_closed());
  EXPECT_TRUE(next_snapshot(first));  // the first is still served
}

TEST(ServerSocket, OversizedPrefixGetsAnErrorAndOthersAreStillServed) {
  server::ServerConfig config;
  config.max_message_bytes = 1024;
  RunningServer running(config);
  SocketClient good(running.port());
  ASSERT_TRUE(good.join("good"));
  SocketClient bad(running.port());
  std::string prefix;
  wire::append_varint_prefix(std::uint64_t{1} << 40, prefix);
  bad.send_raw(prefix);
  const auto error = next_error(bad);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->code(), physics::wire::ERROR_MESSAGE_TOO_LARGE);
  EXPECT_TRUE(bad.wait_closed());
  const auto before = next_snapshot(good);
  const auto after = next_snapshot(good);
  ASSERT_TRUE(before && after);
  EXPECT_GT(after->tick(), before->tick());
}

TEST(ServerSocket, BytesThatDoNotParseAreMalformed) {
  RunningServer running({});
  SocketClient client(running.port());
  client.send_raw(std::string("\x03\xff\xff\xff", 4));  // a frame of 3 bytes of junk
  const auto error = next_error(client);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->code(), physics::wire::ERROR_MALFORMED);
  EXPECT_TRUE(client.wait_closed());
  EXPECT_TRUE(
      eventually([&] { return drops(running.server, server::DropReason::Malformed) == 1u; }));
}

TEST(ServerSocket, InputBeforeHelloIsUnexpected) {
  RunningServer running({});
  SocketClient client(running.port());
  client.send(wire::make_input(1, 1.0, 1.0));
  const auto error = next_error(client);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->code(), physics::wire::ERROR_UNEXPECTED_MESSAGE);
  EXPECT_TRUE(client.wait_closed());
}

TEST(ServerSocket, NanAndFarFutureInputsGetErrorsAndTheSessionStays) {
  RunningServer running({});
  SocketClient client(running.port());
  const auto welcome = client.join("nan");
  ASSERT_TRUE(welcome);
  client.send(
      wire::make_input(welcome->current_tick() + 2, std::numeric_limits<double>::quiet_NaN(), 0.0));
  auto error = next_error(client);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->code(), physics::wire::ERROR_INVALID_INPUT);
  EXPECT_FALSE(error->fatal());
  client.send(wire::make_input(welcome->current_tick() + 1000000, 1.0, 0.0));
  error = next_error(client);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->code(), physics::wire::ERROR_TICK_TOO_FAR_AHEAD);
  EXPECT_FALSE(error->fatal());
  EXPECT_TRUE(next_snapshot(client));  // still served
  const auto stats = running.server.stats();
  EXPECT_EQ(stats.invalid_inputs, 1u);
  EXPECT_EQ(stats.far_future_inputs, 1u);
  EXPECT_EQ(stats.dropped_total(), 0u);
}

// A client that never reads (nor acknowledges) costs its window and no more: the
// server holds at most that many of its snapshots, and drops it as too slow once a
// write to it has stalled for idle_timeout. The reader is served all along.
TEST(ServerSocket, ClientThatNeverReadsHoldsItsWindowAndIsDroppedAsTooSlow) {
  server::ServerConfig config;
  config.tick_rate = 500.0;
  config.idle_timeout = 400ms;
  config.socket_send_buffer_bytes = 4096;
  RunningServer running(config, scene::default_scene());
  SocketClient reader(running.port());
  ASSERT_TRUE(reader.join("reader"));
  SocketClient sleeper(running.port(), 4096);
  sleeper.send(server_test::full_view_hello("sleeper"));  // then never reads
  // Margins, in wall time by the steady clock, so that a slow machine or
  // ThreadSanitizer changes only how long this takes: both clients ping whenever a
  // quarter of idle_timeout has passed (4x margin against being dropped as idle;
  // the sleeper sends, so it is "too slow", not "idle"), and the drop is awaited
  // for 25 timeouts (the window fills in 64 ticks, 0.13 s; then one timeout).
  const auto keep_alive = config.idle_timeout / 4;
  const auto deadline = std::chrono::steady_clock::now() + 25 * config.idle_timeout;
  auto next_ping = std::chrono::steady_clock::now();
  std::uint64_t last_tick = 0;
  std::uint64_t nonce = 0;
  bool dropped = false;
  while (!dropped && std::chrono::steady_clock::now() < deadline) {
    if (std::chrono::steady_clock::now() >= next_ping) {
      physics::wire::ClientMessage ping;
      ping.mutable_ping()->set_nonce(++nonce);
      reader.send(ping);
      sleeper.send(ping);
      next_ping = std::chrono::steady_clock::now() + keep_alive;
    }
    const auto snapshot = next_snapshot(reader);
    ASSERT_TRUE(snapshot);
    EXPECT_GT(snapshot->tick(), last_tick);
    last_tick = snapshot->tick();
    dropped = drops(running.server, server::DropReason::TooSlow) == 1;
  }
  EXPECT_TRUE(dropped);
  EXPECT_EQ(drops(running.server, server::DropReason::Idle), 0u);
  const auto stats = running.server.stats();
  // Its window (64) filled, and then its ticks were skipped rather than queued.
  EXPECT_GT(stats.skipped_snapshots, 0u);
  EXPECT_LE(stats.peak_queued_snapshots, 64u);
  EXPECT_TRUE(eventually([&] { return running.server.stats().connected_clients == 1u; }));
  const auto more = next_snapshot(reader);
  ASSERT_TRUE(more);
  EXPECT_GT(more->tick(), last_tick);
}

TEST(ServerSocket, ClientThatSendsNothingIsDroppedAsIdle) {
  server::ServerConfig config;
  config.idle_timeout = 300ms;
  RunningServer running(config);
  // The server's idle clock starts no earlier than the connect, so the Error cannot
  // come sooner than one timeout after this; every wait for it or for the drop is
  // bounded by 20 timeouts (6 s), a margin for a slow machine or ThreadSanitizer.
  const auto connected = std::chrono::steady_clock::now();
  const auto margin = 20 * config.idle_timeout;
  SocketClient quiet(running.port());
  ASSERT_TRUE(quiet.join("quiet"));
  std::optional<physics::wire::Error> error;
  for (auto left = margin; !error && left > 0ms;
       left = std::chrono::duration_cast<std::chrono::milliseconds>(
           connected + margin - std::chrono::steady_clock::now())) {
    const auto message = quiet.receive(left);  // snapshots (not acknowledged), the Error
    if (!message) break;
    if (message->has_error()) error = message->error();
  }
  const auto waited = std::chrono::steady_clock::now() - connected;
  ASSERT_TRUE(error);
  EXPECT_EQ(error->code(), physics::wire::ERROR_TOO_SLOW);
  EXPECT_GE(waited, config.idle_timeout) << "dropped before the idle timeout";
  EXPECT_TRUE(quiet.wait_closed(margin));
  EXPECT_TRUE(
      eventually([&] { return drops(running.server, server::DropReason::Idle) == 1; }, margin));
  EXPECT_TRUE(eventually([&] { return running.server.stats().connected_clients == 0; }, margin));
}

TEST(ServerSocket, ByeRemovesTheBodyForEveryoneElse) {
  RunningServer running({});
  SocketClient stay(running.port());
  ASSERT_TRUE(stay.join("stay"));
  SocketClient go(running.port());
  const auto welcome = go.join("go");
  ASSERT_TRUE(welcome);
  // A body that joins and leaves between two snapshots is never announced at all;
  // wait until the staying client has seen it.
  bool seen = false;
  for (int i = 0; i < 600 && !seen; ++i) {
    const auto snapshot = next_snapshot(stay);
    ASSERT_TRUE(snapshot);
    for (const auto& body : snapshot->bodies()) seen |= body.body_id() == welcome->body_id();
  }
  ASSERT_TRUE(seen);
  physics::wire::ClientMessage bye;
  bye.mutable_bye()->set_reason("done");
  go.send(bye);
  EXPECT_TRUE(go.wait_closed());
  bool removed = false;
  for (int i = 0; i < 600 && !removed; ++i) {
    const auto snapshot = next_snapshot(stay);
    ASSERT_TRUE(snapshot);
    for (const auto id : snapshot->removed()) removed |= id == welcome->body_id();
  }
  EXPECT_TRUE(removed);
  EXPECT_TRUE(
      eventually([&] { return drops(running.server, server::DropReason::ClientBye) == 1u; }));
}

TEST(ServerSocket, LockstepHashesEqualTheSameInputsSteppedInProcess) {
  server::ServerConfig config;
  config.lockstep = true;
  config.lockstep_timeout = 10000ms;  // long: every tick must wait for both inputs
  RunningServer running(config, scene::default_scene());
  SocketClient a(running.port());
  SocketClient b(running.port());
  const auto wa = a.join("a");
  const auto wb = b.join("b");
  ASSERT_TRUE(wa && wb);
  EXPECT_EQ(wa->current_tick(), 0u);
  EXPECT_EQ(wb->current_tick(), 0u);

  server::Simulation replay(scene::default_scene());
  replay.join(wa->client_id());
  replay.join(wb->client_id());
  // Simulation is the server's own tick logic, so a bug in it would be in both. A
  // plain phys::World, built from the scene with the players' bodies added as the
  // room adds them (room.h: the player template, dynamic, at rest, at the first
  // free spawn point; the first two are free here), is a second, independent oracle.
  const scene::SceneDef& scene = scene::default_scene();
  phys::World plain = scene::build_world(scene);
  auto add_player = [&](phys::Vec2 at) {
    phys::BodyDef def = scene.player;
    def.motion = phys::Motion::Dynamic;
    def.position = at;
    def.velocity = {};
    def.acceleration = {};
    return plain.add_body(def);
  };
  const phys::BodyId pa = add_player(scene.spawn_points[0]);
  const phys::BodyId pb = add_player(scene.spawn_points[1]);
  EXPECT_EQ(wa->body_id(), pa.packed());
  EXPECT_EQ(wb->body_id(), pb.packed());
  constexpr std::uint64_t kTicks = 40;
  std::vector<std::uint64_t> expected;
  std::vector<std::uint64_t> expected_plain;
  for (std::uint64_t tick = 1; tick <= kTicks; ++tick) {
    const phys::Vec2 ia{30.0 * std::sin(0.2 * static_cast<double>(tick)), 12.0};
    const phys::Vec2 ib{-20.0, 25.0 * std::cos(0.3 * static_cast<double>(tick))};
    a.send(wire::make_input(tick, ia.x, ia.y));
    b.send(wire::make_input(tick, ib.x, ib.y));
    replay.submit_input(wa->client_id(), tick, ia);
    replay.submit_input(wb->client_id(), tick, ib);
    replay.step_tick();
    expected.push_back(replay.world().state_hash());
    // The input of tick t is the acceleration during step t (both under the scene's
    // max_acceleration of 50, so none is clamped); dt = 1 / the scene's tick rate.
    plain.set_acceleration(pa, ia);
    plain.set_acceleration(pb, ib);
    plain.step(1.0 / scene.tick_rate);
    expected_plain.push_back(plain.state_hash());
  }
  for (std::uint64_t tick = 1; tick <= kTicks; ++tick) {
    const auto sa = next_snapshot(a);
    const auto sb = next_snapshot(b);
    ASSERT_TRUE(sa && sb);
    EXPECT_EQ(sa->tick(), tick);
    EXPECT_EQ(sb->tick(), tick);
    EXPECT_EQ(sa->state_hash(), expected[tick - 1]) << "tick " << tick;
    EXPECT_EQ(sb->state_hash(), expected[tick - 1]) << "tick " << tick;
    EXPECT_EQ(sa->state_hash(), expected_plain[tick - 1]) << "plain world, tick " << tick;
    EXPECT_EQ(sa->last_applied_input_tick(), tick);
  }
  // Stats are published just after the snapshots are queued.
  EXPECT_TRUE(eventually([&] { return running.server.stats().current_tick == kTicks; }));
  EXPECT_EQ(running.server.stats().lockstep_timeouts, 0u);
}

TEST(ServerSocket, LockstepTimeoutReusesTheMissingInputAndCountsIt) {
  server::ServerConfig config;
  config.lockstep = true;
  config.lockstep_timeout = 20ms;
  RunningServer running(config);
  SocketClient eager(running.port());
  SocketClient absent(running.port());
  ASSERT_TRUE(eager.join("eager"));
  ASSERT_TRUE(absent.join("absent"));
  // No tick steps while nobody sends anything.
  EXPECT_FALSE(eager.receive(100ms));
  EXPECT_EQ(running.server.stats().current_tick, 0u);
  for (std::uint64_t tick = 1; tick <= 3; ++tick) eager.send(wire::make_input(tick, 1.0, 0.0));
  for (std::uint64_t tick = 1; tick <= 3; ++tick) {
    const auto snapshot = next_snapshot(eager);
    ASSERT_TRUE(snapshot);
    EXPECT_EQ(snapshot->tick(), tick);
  }
  // Stats are published just after the snapshots are queued.
  EXPECT_TRUE(eventually([&] {
    const auto stats = running.server.stats();
    return stats.current_tick == 3u && stats.lockstep_timeouts == 3u;
  }));
  EXPECT_EQ(running.server.stats().reused_inputs, 3u);
}

TEST(ServerSocket, StopSendsShuttingDownAndRunReturns) {
  server::ServerConfig config;
  config.port = 0;
  server::Server server(config, server_test::free_space_scene());
  std::thread thread([&] { server.run(); });
  SocketClient client(server.port());
  ASSERT_TRUE(client.join("bye"));
  server.stop();
  server.stop();  // idempotent
  const auto error = next_error(client);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->code(), physics::wire::ERROR_SHUTTING_DOWN);
  EXPECT_TRUE(client.wait_closed());
  thread.join();  // run() returned
  EXPECT_EQ(server.stats().dropped.at(server::DropReason::ShuttingDown), 1u);
}

}  // namespace

namespace {

TEST(ServerSocket, FramesLargerThanOneWriteArriveWhole) {
  // 3000 balls: a Welcome of ~150 kB and snapshots of ~130 kB, far more than one
  // write_some moves, so every frame is written in several pieces.
  scene::SceneDef scene = server_test::free_space_scene();
  for (int i = 0; i < 3000; ++i) {
    phys::BodyDef ball = scene.player;
    ball.position = {static_cast<double>(i % 60) * 3.0, 100.0 + static_cast<double>(i / 60) * 3.0};
    scene.bodies.push_back(ball);
  }
  server::ServerConfig config;
  config.socket_send_buffer_bytes = 16384;  // no frame fits in the kernel at once
  RunningServer running(config, scene);
  SocketClient first(running.port());
  SocketClient second(running.port());
  const auto w1 = first.join("first");
  const auto w2 = second.join("second");
  ASSERT_TRUE(w1 && w2);
  EXPECT_EQ(w1->bodies_size(), 3001);
  for (int i = 0; i < 10; ++i) {
    for (SocketClient* client : {&first, &second}) {
      const auto snapshot = next_snapshot(*client);
      ASSERT_TRUE(snapshot) << "snapshot " << i;
      // 3000 balls and one or two players (the first may see ticks before the second).
      EXPECT_GE(snapshot->bodies_size(), 3001);
      EXPECT_LE(snapshot->bodies_size(), 3002);
    }
  }
}

}  // namespace
