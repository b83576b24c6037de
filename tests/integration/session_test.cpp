// The ordinary life of a session, and the client library's own states: Welcome
// contents, Ping/Pong, Bye, server shutdown, connect failures, a server that never
// answers, a server that sends garbage.
#include <gtest/gtest.h>

#include <asio.hpp>
#include <cmath>
#include <thread>

#include "harness.h"
#include "test_scenes.h"

namespace itest {
namespace {

TEST(Session, WelcomeDescribesTheSceneAndTheOwnBody) {
  const scene::SceneDef& scene = scene::default_scene();
  RunningServer server(test_config(), scene);
  client::Client player(server.client_config("welcome"));
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  const client::Welcome& welcome = player.welcome();
  EXPECT_EQ(welcome.protocol_version, client::kProtocolVersion);
  EXPECT_DOUBLE_EQ(welcome.tick_rate, scene.tick_rate);
  EXPECT_DOUBLE_EQ(welcome.max_acceleration, scene.max_acceleration);
  EXPECT_EQ(welcome.scene_name, scene.name);
  EXPECT_FALSE(welcome.lockstep);
  // Every scene body plus our own.
  EXPECT_EQ(welcome.bodies.size(), scene.bodies.size() + 1);
  std::size_t statics = 0;
  bool own_found = false;
  for (const auto& body : welcome.bodies) {
    statics += body.is_static ? 1 : 0;
    if (body.body_id == welcome.body_id) {
      own_found = true;
      EXPECT_FALSE(body.is_static);
    }
  }
  EXPECT_TRUE(own_found);
  std::size_t scene_statics = 0;
  for (const auto& def : scene.bodies) scene_statics += def.motion == phys::Motion::Static ? 1 : 0;
  EXPECT_EQ(statics, scene_statics);
  EXPECT_EQ(welcome.client_id, 1u);  // the first connection accepted
  // Then snapshots in tick order, each of every dynamic body, our own among them.
  std::uint64_t previous = welcome.current_tick;
  for (int i = 0; i < 10; ++i) {
    auto snapshot = player.next_snapshot(3s);
    ASSERT_TRUE(snapshot.has_value()) << player.last_error().to_string();
    ASSERT_TRUE(snapshot->own.has_value());
    EXPECT_NE(snapshot->find(welcome.body_id), nullptr);
    EXPECT_GT(snapshot->tick, previous);
    previous = snapshot->tick;
    EXPECT_EQ(snapshot->bodies.size(), welcome.bodies.size() - statics);
  }
  EXPECT_EQ(server.stats().connected_clients, 1u);
}

TEST(Session, InputInRealTimeIsAppliedAndMovesTheBodyThatWay) {
  RunningServer server(test_config(), free_flight_scene(false));
  client::Client player(server.exact_client_config("realtime"));
  ASSERT_TRUE(player.connect(3s));
  const std::uint64_t tick = player.welcome().current_tick + 3;
  ASSERT_TRUE(player.send_input(tick, 10.0, -5.0));
  auto applied = player.wait_for_snapshot(3s, [&](const client::Snapshot& s) {
    return s.has_applied_input && s.last_applied_input_tick >= tick && s.tick > tick + 5;
  });
  ASSERT_TRUE(applied.has_value()) << player.last_error().to_string();
  ASSERT_TRUE(applied->own.has_value());
  EXPECT_GT(applied->own->velocity.x, 0.0);
  EXPECT_LT(applied->own->velocity.y, 0.0);
  EXPECT_DOUBLE_EQ(applied->own->velocity.x, -2.0 * applied->own->velocity.y);
}

TEST(Session, PingIsAnsweredWithPong) {
  RunningServer server(test_config(), scene::default_scene());
  client::Client player(server.client_config("ping"));
  ASSERT_TRUE(player.connect(3s));
  ASSERT_TRUE(player.send_ping(4242));
  auto pong = player.next_pong(3s);
  ASSERT_TRUE(pong.has_value());
  EXPECT_EQ(pong->nonce, 4242u);
  EXPECT_GT(pong->client_time_ns, 0u);
  EXPECT_GE(pong->server_tick, player.welcome().current_tick);
}

TEST(Session, ByeRemovesTheBody) {
  RunningServer server(test_config(), scene::default_scene());
  client::Client stay(server.client_config("stay"));
  client::Client leave(server.client_config("leave"));
  ASSERT_TRUE(stay.connect(3s));
  ASSERT_TRUE(leave.connect(3s));
  const std::uint64_t body = leave.welcome().body_id;
  ASSERT_TRUE(stay.wait_for_snapshot(3s, [&](const auto& s) { return s.find(body) != nullptr; }));
  leave.disconnect("done");
  EXPECT_EQ(leave.state(), client::ConnectionState::Disconnected);
  bool listed_as_removed = false;
  auto gone = stay.wait_for_snapshot(3s, [&](const client::Snapshot& s) {
    for (auto id : s.removed) listed_as_removed |= id == body;
    return s.find(body) == nullptr;
  });
  ASSERT_TRUE(gone.has_value());
  EXPECT_TRUE(listed_as_removed);
  EXPECT_TRUE(
      eventually([&] { return dropped(server.stats(), server::DropReason::ClientBye) == 1; }));
  // The server holds nothing of it: only the staying client's connection is open.
  EXPECT_TRUE(eventually([&] {
    const auto stats = server.stats();
    return stats.open_connections == 1 && stats.connected_clients == 1;
  }));
}

// Server::stop() (twice: it is idempotent) sends every client ERROR_SHUTTING_DOWN,
// closes it, and run() returns.
TEST(Session, ServerShutdownIsReportedToTheClientAndRunReturns) {
  RunningServer server(test_config(), scene::default_scene());
  client::Client player(server.client_config("shutdown"));
  ASSERT_TRUE(player.connect(3s));
  server.get().stop();
  server.get().stop();
  auto error = player.next_error(3s);
  ASSERT_TRUE(error.has_value()) << player.last_error().to_string();
  EXPECT_EQ(error->code, client::ErrorCode::ShuttingDown);
  EXPECT_TRUE(error->fatal);
  EXPECT_EQ(player.state(), client::ConnectionState::ConnectionLost);
  EXPECT_FALSE(player.send_input(1, 0.0, 0.0));
  server.stop();  // joins the server's thread: run() returned
  EXPECT_EQ(dropped(server.stats(), server::DropReason::ShuttingDown), 1u);
}

TEST(ClientStates, ConnectToAClosedPortFails) {
  std::uint16_t port = 0;
  {
    asio::io_context context;
    asio::ip::tcp::acceptor acceptor(context, {asio::ip::make_address("127.0.0.1"), 0});
    port = acceptor.local_endpoint().port();
  }
  client::ClientConfig config;
  config.port = port;
  client::Client player(config);
  EXPECT_FALSE(player.connect(2s));
  EXPECT_EQ(player.state(), client::ConnectionState::ConnectFailed);
  EXPECT_FALSE(player.last_error().server.has_value());
  EXPECT_FALSE(player.send_input(1, 0.0, 0.0));
}

TEST(ClientStates, ServerThatNeverAnswersTimesOut) {
  asio::io_context context;
  // Listening is enough: the kernel completes the handshake; nobody ever answers.
  asio::ip::tcp::acceptor acceptor(context, {asio::ip::make_address("127.0.0.1"), 0});
  client::ClientConfig config;
  config.port = acceptor.local_endpoint().port();
  client::Client player(config);
  EXPECT_FALSE(player.connect(300ms));
  EXPECT_EQ(player.state(), client::ConnectionState::WelcomeTimedOut);
}

TEST(ClientStates, GarbageFromTheServerIsAProtocolError) {
  asio::io_context context;
  asio::ip::tcp::acceptor acceptor(context, {asio::ip::make_address("127.0.0.1"), 0});
  std::thread fake_server([&] {
    asio::ip::tcp::socket socket(context);
    acceptor.accept(socket);
    const std::string garbage = "\x05\xFF\xFF\xFF\xFF\xFF";  // a frame that does not parse
    asio::write(socket, asio::buffer(garbage));
    std::error_code ignored;
    std::array<char, 256> sink{};
    socket.read_some(asio::buffer(sink), ignored);  // until the client closes
  });
  client::ClientConfig config;
  config.port = acceptor.local_endpoint().port();
  client::Client player(config);
  EXPECT_FALSE(player.connect(3s));
  EXPECT_EQ(player.state(), client::ConnectionState::ProtocolError);
  fake_server.join();
}

}  // namespace
}  // namespace itest
