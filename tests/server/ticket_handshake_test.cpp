// Admission by connect ticket, without sockets: a Hello without a valid ticket is
// refused before anything is held (each reason with its own text), a ticket admits
// one connection per player id at a time, and in a lockstep lobby a seat belongs to
// the ticket's player: strangers never hold it, whatever order the players arrive in.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "handshake.h"
#include "server/simulation.h"
#include "test_scene.h"
#include "ticket/ticket.h"
#include "wire/messages.h"

namespace {

using server::Handshake;
using server::HelloDecision;
using Outcome = HelloDecision::Outcome;
using server::DropReason;
namespace pw = physics::wire;

constexpr std::uint64_t kNow = 1'800'000'000;  // unix seconds, as the network layer reads them
constexpr std::uint64_t kPlayerA = 1001;
constexpr std::uint64_t kPlayerB = 1002;
constexpr std::uint64_t kStranger = 6666;

ticket::Key test_key(std::uint8_t fill = 7) {
  ticket::Key key{};
  key.fill(fill);
  return key;
}

std::string ticket_for(std::uint64_t player, std::optional<std::uint32_t> seat = std::nullopt,
                       const std::string& room = "", std::uint64_t expires_at = kNow + 60,
                       const ticket::Key& key = test_key()) {
  ticket::Ticket t;
  t.player_id = player;
  t.seat = seat;
  t.room = room;
  t.expires_at = expires_at;
  t.nonce = ticket::new_nonce();
  return ticket::mint(t, key);
}

pw::Hello hello_with(const std::string& access_token) {
  pw::Hello message;
  message.set_protocol_version(wire::kProtocolVersion);
  message.set_client_name("player");
  message.set_access_token(access_token);
  return message;
}

server::ServerConfig ticket_config(int lockstep_players = 0) {
  server::ServerConfig config;
  config.max_clients = 8;
  config.ticket_key = test_key();
  config.lockstep = lockstep_players > 0;
  config.lockstep_players = lockstep_players;
  return config;
}

struct Lobby {
  server::Simulation simulation{server_test::free_space_scene()};
  Handshake handshake{ticket_config(2)};
  HelloDecision hello(server::ClientId client, const std::string& access_token,
                      std::optional<std::uint32_t> hello_seat = std::nullopt) {
    pw::Hello message = hello_with(access_token);
    if (hello_seat) message.set_seat(*hello_seat);
    return handshake.decide(client, false, message, simulation, "10.0.0.1", kNow);
  }
};

void expect_refused(const HelloDecision& decision, pw::ErrorCode code) {
  EXPECT_EQ(decision.outcome, Outcome::Refused);
  EXPECT_EQ(decision.refusal.code, code) << decision.refusal.text;
}

TEST(TicketHandshake, AValidTicketAdmitsAPlayerAndASpectator) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(ticket_config());
  const HelloDecision player =
      handshake.decide(1, false, hello_with(ticket_for(kPlayerA)), simulation, "", kNow);
  ASSERT_EQ(player.outcome, Outcome::Player) << player.refusal.text;
  ASSERT_TRUE(player.ticket.has_value());
  EXPECT_EQ(player.ticket->player_id, kPlayerA);
  pw::Hello watch = hello_with(ticket_for(kPlayerB, std::nullopt, "free space"));
  watch.set_spectate(true);
  EXPECT_EQ(handshake.decide(2, false, watch, simulation, "", kNow).outcome, Outcome::Spectator);
}

// Nothing is held for a Hello without a valid ticket: no seat, no body, no
// subscription, no lobby place; and every reason reads differently.
TEST(TicketHandshake, EachInvalidTicketIsRefusedWithItsOwnReasonHoldingNothing) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(ticket_config(2));
  std::string tampered = ticket_for(kPlayerA);
  tampered[20] = tampered[20] == 'A' ? 'B' : 'A';
  const std::string refused_tokens[] = {
      "",                                                              // missing
      "sesame",                                                        // not a ticket
      ticket_for(kPlayerA, std::nullopt, "", kNow),                    // expired
      tampered,                                                        // a byte changed
      ticket_for(kPlayerA, std::nullopt, "", kNow + 60, test_key(8)),  // another key
      ticket_for(kPlayerA, std::nullopt, "another room"),              // another room
  };
  std::set<std::string> texts;
  server::ClientId client = 1;
  for (const std::string& token : refused_tokens) {
    pw::Hello message = hello_with(token);
    message.set_want_world(true);
    message.mutable_contacts()->set_all(true);
    message.set_seat(1);
    const HelloDecision decision =
        handshake.decide(client++, false, message, simulation, "10.0.0.1", kNow);
    expect_refused(decision, pw::ERROR_BAD_TOKEN);
    EXPECT_EQ(decision.refusal.reason, DropReason::BadToken);
    EXPECT_FALSE(decision.contacts.has_value());
    texts.insert(decision.refusal.text);
    pw::Hello watch = hello_with(token);
    watch.set_spectate(true);
    expect_refused(handshake.decide(client++, false, watch, simulation, "", kNow),
                   pw::ERROR_BAD_TOKEN);
  }
  EXPECT_EQ(texts.size(), std::size(refused_tokens));
  EXPECT_EQ(handshake.seats().taken(), 0u);
  EXPECT_EQ(handshake.lobby_size(), 0u);
  EXPECT_EQ(handshake.spectator_count(), 0u);
  EXPECT_EQ(simulation.world().body_count(), 0u);
  // The same seat then goes to its ticket's player.
  Lobby lobby;
  EXPECT_EQ(lobby.hello(1, ticket_for(kPlayerB, 1)).seat, 1u);
}

TEST(TicketHandshake, ATicketIsRefusedWhileItsPlayerIsConnectedAndAdmitsAgainAfter) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(ticket_config());
  const std::string ticket = ticket_for(kPlayerA);
  ASSERT_EQ(handshake.decide(1, false, hello_with(ticket), simulation, "", kNow).outcome,
            Outcome::Player);
  // The same ticket, and another ticket for the same player, from a second connection.
  for (const std::string& again : {ticket, ticket_for(kPlayerA)}) {
    const HelloDecision second =
        handshake.decide(2, false, hello_with(again), simulation, "", kNow);
    expect_refused(second, pw::ERROR_BAD_TOKEN);
    EXPECT_NE(second.refusal.text.find("connected already"), std::string::npos)
        << second.refusal.text;
  }
  EXPECT_EQ(simulation.room().size(), 1u);
  handshake.leave(1);
  simulation.leave(1);
  EXPECT_EQ(handshake.decide(3, false, hello_with(ticket), simulation, "", kNow).outcome,
            Outcome::Player);
}

TEST(TicketHandshake, TheRoomIsTheScenesNameUnlessTheServerNamesOne) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake by_scene(ticket_config());
  EXPECT_EQ(by_scene
                .decide(1, false, hello_with(ticket_for(kPlayerA, std::nullopt, "free space")),
                        simulation, "", kNow)
                .outcome,
            Outcome::Player);
  server::ServerConfig named = ticket_config();
  named.ticket_room = "match-17";
  Handshake by_name(named);
  const HelloDecision scene_room = by_name.decide(
      2, false, hello_with(ticket_for(kPlayerB, std::nullopt, "free space")), simulation, "", kNow);
  expect_refused(scene_room, pw::ERROR_BAD_TOKEN);
  EXPECT_NE(scene_room.refusal.text.find("match-17"), std::string::npos) << scene_room.refusal.text;
  EXPECT_EQ(by_name
                .decide(3, false, hello_with(ticket_for(kPlayerB, std::nullopt, "match-17")),
                        simulation, "", kNow)
                .outcome,
            Outcome::Player);
}

// A lobby of 2 whose backend gave player A seat 0 and player B seat 1: in either order
// they get their seats and the lobby opens with them.
TEST(TicketHandshake, TheLobbysPlayersGetTheirTicketsSeatsInEitherOrder) {
  for (const bool a_first : {true, false}) {
    Lobby lobby;
    const std::string a = ticket_for(kPlayerA, 0);
    const std::string b = ticket_for(kPlayerB, 1);
    const HelloDecision first = a_first ? lobby.hello(1, a) : lobby.hello(1, b);
    const HelloDecision second = a_first ? lobby.hello(2, b) : lobby.hello(2, a);
    ASSERT_EQ(first.outcome, Outcome::Lobby) << first.refusal.text;
    ASSERT_EQ(second.outcome, Outcome::Lobby) << second.refusal.text;
    EXPECT_EQ(first.seat, a_first ? 0u : 1u);
    EXPECT_EQ(second.seat, a_first ? 1u : 0u);
    EXPECT_TRUE(second.lobby_full);
    const server::LobbyOpening opening = lobby.handshake.open_lobby(lobby.simulation);
    ASSERT_EQ(opening.welcomed.size(), 2u);
    EXPECT_EQ(opening.welcomed[1].client, a_first ? 2u : 1u);  // B's connection in seat 1
  }
}

// Seat 1 is player B's: a stranger (a ticket for another player, or none) never holds
// it, not while B waits in the lobby, nor after B left it; B gets it back.
TEST(TicketHandshake, AStrangerNeverHoldsAnotherPlayersSeat) {
  Lobby lobby;
  ASSERT_EQ(lobby.hello(1, ticket_for(kPlayerB, 1)).outcome, Outcome::Lobby);
  expect_refused(lobby.hello(2, ""), pw::ERROR_BAD_TOKEN);
  expect_refused(lobby.hello(3, ticket_for(kStranger, 1)), pw::ERROR_SEAT_TAKEN);
  expect_refused(lobby.hello(4, ticket_for(kPlayerB, 1)), pw::ERROR_BAD_TOKEN);  // B is here
  lobby.handshake.leave(1);
  EXPECT_FALSE(lobby.handshake.seats().seat_of(1).has_value());
  const HelloDecision held = lobby.hello(5, ticket_for(kStranger, 1));
  expect_refused(held, pw::ERROR_SEAT_TAKEN);
  EXPECT_EQ(held.refusal.text, "seat 1 is held for another player");
  expect_refused(lobby.hello(6, ticket_for(kStranger), 1), pw::ERROR_SEAT_TAKEN);
  expect_refused(lobby.hello(7, ""), pw::ERROR_BAD_TOKEN);
  // Player A takes seat 0; a seatless stranger then finds no seat it may hold.
  ASSERT_EQ(lobby.hello(8, ticket_for(kPlayerA, 0)).seat, 0u);
  const HelloDecision full = lobby.hello(9, ticket_for(kStranger));
  expect_refused(full, pw::ERROR_SERVER_FULL);
  EXPECT_EQ(full.refusal.reason, DropReason::ServerFull);
  EXPECT_FALSE(lobby.handshake.lobby_open());
  const HelloDecision back = lobby.hello(10, ticket_for(kPlayerB, 1));
  ASSERT_EQ(back.outcome, Outcome::Lobby) << back.refusal.text;
  EXPECT_EQ(back.seat, 1u);
  EXPECT_TRUE(back.lobby_full);
  EXPECT_EQ(lobby.handshake.seats().in_seat_order(), (std::vector<server::ClientId>{8, 10}));
}

// A ticket without a seat takes the lowest seat held for nobody, and that seat is
// then its player's: it comes back to the same seat, and others cannot take it.
TEST(TicketHandshake, ASeatlessTicketIsBoundToTheSeatItTook) {
  Lobby lobby;
  const HelloDecision first = lobby.hello(1, ticket_for(kPlayerA));
  ASSERT_EQ(first.outcome, Outcome::Lobby);
  EXPECT_EQ(first.seat, 0u);
  lobby.handshake.leave(1);
  expect_refused(lobby.hello(2, ticket_for(kPlayerB, 0)), pw::ERROR_SEAT_TAKEN);
  EXPECT_EQ(lobby.hello(3, ticket_for(kPlayerB)).seat, 1u);
  EXPECT_EQ(lobby.hello(4, ticket_for(kPlayerA)).seat, 0u);
}

TEST(TicketHandshake, HelloSeatMustAgreeWithTheTicketsSeat) {
  Lobby lobby;
  const HelloDecision other = lobby.hello(1, ticket_for(kPlayerA, 0), 1);
  expect_refused(other, pw::ERROR_SEAT_TAKEN);
  EXPECT_EQ(other.refusal.text, "Hello.seat 1 is not the ticket's seat 0");
  EXPECT_EQ(lobby.hello(2, ticket_for(kPlayerA, 0), 0).seat, 0u);
  // Once A holds seat 0, a ticket of A's naming seat 1 is refused.
  lobby.handshake.leave(2);
  expect_refused(lobby.hello(3, ticket_for(kPlayerA, 1)), pw::ERROR_SEAT_TAKEN);
}

}  // namespace
