// Connect tickets on a real server over loopback (--ticket-key-file): a connection
// without a valid ticket is refused and holds nothing (no Welcome, no world); a
// valid ticket is welcomed, and refused from a second connection while its player is
// connected; in a lockstep lobby of 2 each player gets its ticket's seat, whatever
// order they connect in, and strangers never get seat 1. Waits are bounded reads.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>

#include "server/server.h"
#include "socket_client.h"
#include "test_scene.h"
#include "ticket/ticket.h"

namespace {

using namespace std::chrono_literals;
using server_test::SocketClient;
namespace pw = physics::wire;

constexpr std::uint64_t kPlayerA = 11;
constexpr std::uint64_t kPlayerB = 22;
constexpr std::uint64_t kStranger = 99;

ticket::Key test_key() {
  ticket::Key key{};
  key.fill(0x5a);
  return key;
}

std::string ticket_for(std::uint64_t player, std::optional<std::uint32_t> seat = std::nullopt) {
  ticket::Ticket t;
  t.player_id = player;
  t.seat = seat;
  t.room = "free space";  // the test scene's name
  t.expires_at = static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::seconds>(
                                                std::chrono::system_clock::now().time_since_epoch())
                                                .count() +
                                            3600);
  t.nonce = ticket::new_nonce();
  return ticket::mint(t, test_key());
}

struct RunningServer {
  explicit RunningServer(server::ServerConfig config)
      : server((config.port = 0, config.ticket_key = test_key(), config),
               server_test::free_space_scene()),
        thread([this] { server.run(); }) {}
  ~RunningServer() {
    server.stop();
    thread.join();
  }
  server::Server server;
  std::thread thread;
};

pw::ClientMessage hello_with(const std::string& access_token) {
  pw::ClientMessage hello = server_test::full_view_hello("ticket-holder");
  hello.mutable_hello()->set_want_world(true);
  if (!access_token.empty()) hello.mutable_hello()->set_access_token(access_token);
  return hello;
}

// Sends a Hello and returns the first reply: a Welcome, or an Error.
std::optional<pw::ServerMessage> knock(SocketClient& client, const std::string& access_token) {
  client.send(hello_with(access_token));
  return client.receive(5000ms);
}

void expect_refused(SocketClient& client, const std::optional<pw::ServerMessage>& reply,
                    pw::ErrorCode code, const std::string& text_part) {
  ASSERT_TRUE(reply.has_value());
  ASSERT_TRUE(reply->has_error()) << reply->DebugString();
  EXPECT_EQ(reply->error().code(), code) << reply->error().message();
  EXPECT_TRUE(reply->error().fatal());
  EXPECT_NE(reply->error().message().find(text_part), std::string::npos)
      << reply->error().message();
  EXPECT_TRUE(client.wait_closed(5000ms));
}

TEST(TicketSocket, NoTicketIsRefusedAValidOneWelcomedAndReusedWhileConnectedRefused) {
  RunningServer running({});
  const std::uint16_t port = running.server.port();
  SocketClient without(port);
  expect_refused(without, knock(without, ""), pw::ERROR_BAD_TOKEN, "Hello.access_token is empty");
  SocketClient plain_token(port);
  expect_refused(plain_token, knock(plain_token, "sesame"), pw::ERROR_BAD_TOKEN,
                 "not a connect ticket");

  const std::string ticket = ticket_for(kPlayerA);
  auto holder = std::make_unique<SocketClient>(port);
  const auto welcome = knock(*holder, ticket);
  ASSERT_TRUE(welcome && welcome->has_welcome()) << (welcome ? welcome->DebugString() : "none");
  EXPECT_FALSE(welcome->welcome().world_state().empty());  // want_world, and admitted

  SocketClient copy(port);
  expect_refused(copy, knock(copy, ticket), pw::ERROR_BAD_TOKEN, "connected already");
  EXPECT_EQ(running.server.stats().connected_clients, 1u);

  // Once the holder's connection is gone, the same ticket is welcomed again.
  holder.reset();
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (running.server.stats().connected_clients > 0 &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(5ms);
  }
  SocketClient again(port);
  const auto reply = knock(again, ticket);
  ASSERT_TRUE(reply.has_value());
  EXPECT_TRUE(reply->has_welcome()) << reply->DebugString();
}

// A lobby of 2: the backend gave A seat 0 and B seat 1. Strangers come first; then the
// players in the given order; each Welcome names the ticket's seat.
void run_lobby(bool a_first) {
  server::ServerConfig config;
  config.lockstep = true;
  config.lockstep_players = 2;
  config.max_players_per_address = 0;
  RunningServer running(config);
  const std::uint16_t port = running.server.port();
  SocketClient b(port);
  SocketClient a(port);
  if (!a_first) b.send(hello_with(ticket_for(kPlayerB, 1)));
  // Strangers, while seat 1 is free (a_first) or B's: without a ticket, and with a
  // ticket of another player's naming seat 1 or asking Hello.seat 1.
  SocketClient no_ticket(port);
  expect_refused(no_ticket, knock(no_ticket, ""), pw::ERROR_BAD_TOKEN, "empty");
  if (!a_first) {
    SocketClient stranger(port);
    expect_refused(stranger, knock(stranger, ticket_for(kStranger, 1)), pw::ERROR_SEAT_TAKEN,
                   "held for another player");
  }
  a.send(hello_with(ticket_for(kPlayerA, 0)));
  if (a_first) b.send(hello_with(ticket_for(kPlayerB, 1)));
  const auto welcome_a = a.receive(5000ms);
  const auto welcome_b = b.receive(5000ms);
  ASSERT_TRUE(welcome_a && welcome_a->has_welcome()) << (welcome_a ? welcome_a->DebugString() : "");
  ASSERT_TRUE(welcome_b && welcome_b->has_welcome()) << (welcome_b ? welcome_b->DebugString() : "");
  EXPECT_EQ(welcome_a->welcome().seat(), 0u);
  EXPECT_EQ(welcome_b->welcome().seat(), 1u);
  // Full now: a stranger's ticket gets no seat.
  SocketClient late(port);
  expect_refused(late, knock(late, ticket_for(kStranger)), pw::ERROR_SERVER_FULL, "full");
}

TEST(TicketSocket, TheLobbysPlayersGetTheirTicketsSeatsWhenAConnectsFirst) { run_lobby(true); }

TEST(TicketSocket, TheLobbysPlayersGetTheirTicketsSeatsWhenBConnectsFirst) { run_lobby(false); }

TEST(TicketSocket, ATicketKeyAndATokenTogetherAreRefused) {
  server::ServerConfig config;
  config.token = "sesame";
  EXPECT_THROW(RunningServer running(config), std::invalid_argument);
}

}  // namespace
