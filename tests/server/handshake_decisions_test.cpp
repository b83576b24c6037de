// The Hello's decisions without sockets: each check of docs/PROTOCOL.md 3.1 with its
// code, text and drop reason, in the protocol's order (a Hello wrong on several
// counts gets the first check's error), seats, spectators, the lockstep lobby and
// spawning; a refused Hello changes nothing.
#include <gtest/gtest.h>

#include <string>

#include "handshake.h"
#include "server/simulation.h"
#include "test_scene.h"
#include "wire/messages.h"

namespace {

using server::Handshake;
using server::HelloDecision;
using Outcome = HelloDecision::Outcome;
using server::DropReason;
namespace pw = physics::wire;

pw::Hello hello(const std::string& name = "player") {
  pw::Hello message;
  message.set_protocol_version(wire::kProtocolVersion);
  message.set_client_name(name);
  return message;
}

pw::Hello spectator_hello() {
  pw::Hello message = hello("watcher");
  message.set_spectate(true);
  return message;
}

server::ServerConfig config_with(int max_clients, int max_spectators = 16) {
  server::ServerConfig config;
  config.max_clients = max_clients;
  config.max_spectators = max_spectators;
  return config;
}

server::ServerConfig lobby_config(int players, int max_clients) {
  server::ServerConfig config = config_with(max_clients);
  config.lockstep = true;
  config.lockstep_players = players;
  return config;
}

// free_space_scene inside world bounds that hold one player's ball at the first
// spawn point (0, 0) and nothing else: the second body has nowhere to go.
scene::SceneDef one_place_scene() {
  scene::SceneDef scene = server_test::free_space_scene();
  scene.world.has_bounds = true;
  scene.world.bounds = {{-0.6, -0.6}, {0.6, 0.6}};
  return scene;
}

void expect_refused(const HelloDecision& decision, pw::ErrorCode code, DropReason reason) {
  EXPECT_EQ(decision.outcome, Outcome::Refused);
  EXPECT_EQ(decision.refusal.code, code) << decision.refusal.text;
  EXPECT_EQ(decision.refusal.reason, reason) << decision.refusal.text;
}

// What a Hello may change: a refused one must leave all of it as it was.
struct Counts {
  std::size_t seats_taken, players, lobby, spectators, bodies;
  bool operator==(const Counts&) const = default;
};
Counts counts_of(const Handshake& handshake, const server::Simulation& simulation) {
  return {handshake.seats().taken(), simulation.room().size(), handshake.lobby_size(),
          handshake.spectator_count(), simulation.world().body_count()};
}

TEST(HandshakeDecisions, APlainHelloIsWelcomedAsAPlayerWithABodyAtTheFirstSpawnPoint) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(config_with(4));
  const HelloDecision decision = handshake.decide(1, false, hello("ann"), simulation);
  ASSERT_EQ(decision.outcome, Outcome::Player);
  EXPECT_EQ(decision.name, "ann");
  EXPECT_EQ(decision.seat, 0u);
  ASSERT_TRUE(decision.body.is_valid());
  EXPECT_EQ(simulation.body_of(1), decision.body);
  EXPECT_EQ(simulation.world().body(decision.body)->position.x, 0.0);
  EXPECT_EQ(handshake.seats().seat_of(1), 0u);
  EXPECT_FALSE(decision.contacts.has_value());  // none asked for
  EXPECT_EQ(decision.view.window, wire::ViewSettings{}.window);
}

TEST(HandshakeDecisions, ASecondHelloIsRefusedBeforeAnyOtherCheck) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(config_with(4));
  pw::Hello wrong = hello();
  wrong.set_protocol_version(wire::kProtocolVersion + 1);
  const HelloDecision decision = handshake.decide(1, true, wrong, simulation);
  expect_refused(decision, pw::ERROR_UNEXPECTED_MESSAGE, DropReason::UnexpectedMessage);
  EXPECT_EQ(decision.refusal.text, "a second Hello on the same connection");
}

// A protocol 3 client that asked for the relay could not tell whether it runs the
// game's rules (Welcome.rules_run_here), so it is refused.
TEST(HandshakeDecisions, TheVersionBeforeIsRefused) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(config_with(4));
  pw::Hello old = hello();
  old.set_protocol_version(3);
  ASSERT_EQ(wire::kProtocolVersion, 4u);
  const HelloDecision decision = handshake.decide(1, false, old, simulation);
  expect_refused(decision, pw::ERROR_PROTOCOL_VERSION, DropReason::ProtocolVersion);
  EXPECT_EQ(decision.refusal.text,
            "client speaks protocol version 3, this server speaks version 4");
}

TEST(HandshakeDecisions, WrongVersionNamesBothVersions) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(config_with(4));
  pw::Hello wrong = hello();
  wrong.set_protocol_version(wire::kProtocolVersion + 6);
  const Counts before = counts_of(handshake, simulation);
  const HelloDecision decision = handshake.decide(1, false, wrong, simulation);
  expect_refused(decision, pw::ERROR_PROTOCOL_VERSION, DropReason::ProtocolVersion);
  EXPECT_EQ(decision.refusal.text,
            "client speaks protocol version " + std::to_string(wire::kProtocolVersion + 6) +
                ", this server speaks version " + std::to_string(wire::kProtocolVersion));
  EXPECT_EQ(counts_of(handshake, simulation), before);
}

TEST(HandshakeDecisions, AMissingOrWrongTokenIsRefusedAndTheRightOneAccepted) {
  server::Simulation simulation(server_test::free_space_scene());
  server::ServerConfig config = config_with(4);
  config.token = "s3cret";
  Handshake handshake(config);
  const HelloDecision missing = handshake.decide(1, false, hello(), simulation);
  expect_refused(missing, pw::ERROR_BAD_TOKEN, DropReason::BadToken);
  EXPECT_EQ(missing.refusal.text, "this server requires an access token");
  for (const char* token : {"s3cre", "s3crett", "S3cret", "x"}) {
    pw::Hello wrong = hello();
    wrong.set_access_token(token);
    const HelloDecision decision = handshake.decide(2, false, wrong, simulation);
    expect_refused(decision, pw::ERROR_BAD_TOKEN, DropReason::BadToken);
    EXPECT_EQ(decision.refusal.text, "wrong access token") << token;
  }
  EXPECT_EQ(simulation.room().size(), 0u);
  pw::Hello right = hello();
  right.set_access_token("s3cret");
  EXPECT_EQ(handshake.decide(3, false, right, simulation).outcome, Outcome::Player);
}

TEST(HandshakeDecisions, WithoutATokenConfiguredAnyTokenIsAccepted) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(config_with(4));
  pw::Hello message = hello();
  message.set_access_token("anything");
  EXPECT_EQ(handshake.decide(1, false, message, simulation).outcome, Outcome::Player);
}

TEST(HandshakeDecisions, TheTokenComparisonNeedsEveryByteAndTheLength) {
  EXPECT_TRUE(server::same_token("abc", "abc"));
  EXPECT_TRUE(server::same_token("", ""));
  EXPECT_FALSE(server::same_token("ab", "abc"));
  EXPECT_FALSE(server::same_token("abcd", "abc"));
  EXPECT_FALSE(server::same_token("abd", "abc"));
  EXPECT_FALSE(server::same_token("", "abc"));
  EXPECT_FALSE(server::same_token("abc", ""));
  // A NUL past the end of the expected token is not a match either.
  EXPECT_FALSE(server::same_token(std::string("abc\0", 4), "abc"));
}

TEST(HandshakeDecisions, AnInvalidViewIsRefusedNamingTheField) {
  server::Simulation simulation(server_test::free_space_scene());
  server::ServerConfig config = config_with(4);
  config.max_snapshot_window = 20;
  Handshake handshake(config);
  pw::Hello wrong = hello();
  wrong.mutable_view()->set_window(21);
  const HelloDecision decision = handshake.decide(1, false, wrong, simulation);
  expect_refused(decision, pw::ERROR_INVALID_VIEW, DropReason::InvalidView);
  EXPECT_EQ(decision.refusal.text, "view.window must be in [1, 20] snapshots, got 21");
  pw::Hello fine = hello();
  fine.mutable_view()->set_window(20);
  const HelloDecision accepted = handshake.decide(2, false, fine, simulation);
  ASSERT_EQ(accepted.outcome, Outcome::Player);
  EXPECT_EQ(accepted.view.window, 20u);
}

TEST(HandshakeDecisions, ContactSubscriptionsAreCheckedForPlayersAndSpectators) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(config_with(4));
  pw::Hello greedy = hello();
  greedy.mutable_contacts()->set_all(true);
  const HelloDecision refused = handshake.decide(1, false, greedy, simulation);
  expect_refused(refused, pw::ERROR_INVALID_SUBSCRIPTION, DropReason::InvalidSubscription);
  EXPECT_EQ(refused.refusal.text,
            "contacts: a player hears of its own body's contacts only; leave all and body_ids "
            "empty");
  EXPECT_FALSE(refused.contacts.has_value());

  pw::Hello own = hello();
  own.mutable_contacts();  // present and empty: the player's own body
  const HelloDecision player = handshake.decide(2, false, own, simulation);
  ASSERT_EQ(player.outcome, Outcome::Player);
  ASSERT_TRUE(player.contacts.has_value());
  EXPECT_EQ(player.contacts->kind, server::ContactFilter::Kind::OwnBody);

  pw::Hello neither = spectator_hello();
  neither.mutable_contacts();
  const HelloDecision vague = handshake.decide(3, false, neither, simulation);
  expect_refused(vague, pw::ERROR_INVALID_SUBSCRIPTION, DropReason::InvalidSubscription);
  EXPECT_EQ(vague.refusal.text, "contacts: a spectator gives all or body_ids");

  pw::Hello listed = spectator_hello();
  for (const std::uint64_t id : {9u, 4u, 9u}) listed.mutable_contacts()->add_body_ids(id);
  const HelloDecision spectator = handshake.decide(4, false, listed, simulation);
  ASSERT_EQ(spectator.outcome, Outcome::Spectator);
  ASSERT_TRUE(spectator.contacts.has_value());
  EXPECT_EQ(spectator.contacts->kind, server::ContactFilter::Kind::Bodies);
  EXPECT_EQ(spectator.contacts->bodies, (std::vector<std::uint64_t>{4, 9}));
}

TEST(HandshakeDecisions, AServerFullOfPlayersRefusesTheNextOneButNotASpectator) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(config_with(2));
  ASSERT_EQ(handshake.decide(1, false, hello(), simulation).outcome, Outcome::Player);
  ASSERT_EQ(handshake.decide(2, false, hello(), simulation).outcome, Outcome::Player);
  const Counts before = counts_of(handshake, simulation);
  const HelloDecision full = handshake.decide(3, false, hello(), simulation);
  expect_refused(full, pw::ERROR_SERVER_FULL, DropReason::ServerFull);
  EXPECT_EQ(full.refusal.text, "server full: 2 clients connected");
  EXPECT_EQ(counts_of(handshake, simulation), before);
  EXPECT_EQ(handshake.decide(4, false, spectator_hello(), simulation).outcome, Outcome::Spectator);
  // A player who leaves makes room (and frees its seat) for the next.
  EXPECT_EQ(handshake.leave(1), Handshake::Member::Player);
  ASSERT_TRUE(simulation.leave(1));
  const HelloDecision next = handshake.decide(5, false, hello(), simulation);
  ASSERT_EQ(next.outcome, Outcome::Player);
  EXPECT_EQ(next.seat, 0u);
}

TEST(HandshakeDecisions, PlayersFromOneAddressAreCappedSpectatorsAndOthersAreNot) {
  server::Simulation simulation(server_test::free_space_scene());
  server::ServerConfig config = config_with(10);
  config.max_players_per_address = 2;
  Handshake handshake(config);
  ASSERT_EQ(handshake.decide(1, false, hello(), simulation, "10.0.0.1").outcome, Outcome::Player);
  ASSERT_EQ(handshake.decide(2, false, hello(), simulation, "10.0.0.1").outcome, Outcome::Player);
  const Counts before = counts_of(handshake, simulation);
  const HelloDecision third = handshake.decide(3, false, hello(), simulation, "10.0.0.1");
  expect_refused(third, pw::ERROR_SERVER_FULL, DropReason::AddressFull);
  EXPECT_EQ(third.refusal.text,
            "too many players from 10.0.0.1: 2 joined (--max-players-per-address)");
  EXPECT_EQ(counts_of(handshake, simulation), before);
  EXPECT_EQ(handshake.decide(4, false, spectator_hello(), simulation, "10.0.0.1").outcome,
            Outcome::Spectator);
  EXPECT_EQ(handshake.decide(5, false, hello(), simulation, "10.0.0.2").outcome, Outcome::Player);
  // One leaves: its address may seat one more.
  EXPECT_EQ(handshake.leave(1), Handshake::Member::Player);
  ASSERT_TRUE(simulation.leave(1));
  EXPECT_EQ(handshake.decide(6, false, hello(), simulation, "10.0.0.1").outcome, Outcome::Player);
}

TEST(HandshakeDecisions, SpectatorsHaveTheirOwnCapAndNoRadiusView) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(config_with(1, 1));
  pw::Hello around = spectator_hello();
  around.mutable_view()->set_interest_radius(5.0);
  const HelloDecision radius = handshake.decide(1, false, around, simulation);
  expect_refused(radius, pw::ERROR_INVALID_VIEW, DropReason::InvalidView);
  EXPECT_EQ(radius.refusal.text,
            "view.interest_radius needs a body to be around; a spectator may use "
            "view.interest_rect");

  const HelloDecision first = handshake.decide(2, false, spectator_hello(), simulation);
  ASSERT_EQ(first.outcome, Outcome::Spectator);
  EXPECT_EQ(first.name, "watcher");
  EXPECT_TRUE(handshake.is_spectator(2));
  EXPECT_EQ(simulation.world().body_count(), 0u);  // a spectator has no body
  EXPECT_EQ(handshake.seats().taken(), 0u);        // nor a seat

  const HelloDecision second = handshake.decide(3, false, spectator_hello(), simulation);
  expect_refused(second, pw::ERROR_SERVER_FULL, DropReason::ServerFull);
  EXPECT_EQ(second.refusal.text, "no room to watch: 1 spectators connected");
  EXPECT_FALSE(handshake.is_spectator(3));
  // Spectators do not count against the players.
  EXPECT_EQ(handshake.decide(4, false, hello(), simulation).outcome, Outcome::Player);

  EXPECT_EQ(handshake.leave(2), Handshake::Member::Spectator);
  EXPECT_EQ(handshake.spectator_count(), 0u);
  EXPECT_EQ(handshake.decide(5, false, spectator_hello(), simulation).outcome, Outcome::Spectator);
}

TEST(HandshakeDecisions, NoSpectatorsAtAllWhenTheirCapIsZero) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(config_with(4, 0));
  const HelloDecision decision = handshake.decide(1, false, spectator_hello(), simulation);
  expect_refused(decision, pw::ERROR_SERVER_FULL, DropReason::ServerFull);
  EXPECT_EQ(decision.refusal.text, "no room to watch: 0 spectators connected");
}

TEST(HandshakeDecisions, TakenAndOutOfRangeSeatsAreRefusedAndTheHolderKeepsItsSeat) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(config_with(3));
  pw::Hello second_seat = hello();
  second_seat.set_seat(1);
  const HelloDecision seated = handshake.decide(1, false, second_seat, simulation);
  ASSERT_EQ(seated.outcome, Outcome::Player);
  EXPECT_EQ(seated.seat, 1u);
  // Seat 1 puts the body at spawn point 1.
  EXPECT_EQ(simulation.world().body(seated.body)->position.x, 10.0);

  const Counts before = counts_of(handshake, simulation);
  const HelloDecision taken = handshake.decide(2, false, second_seat, simulation);
  expect_refused(taken, pw::ERROR_SEAT_TAKEN, DropReason::SeatTaken);
  EXPECT_EQ(taken.refusal.text, "seat 1 is taken");

  pw::Hello far = hello();
  far.set_seat(3);
  const HelloDecision out = handshake.decide(3, false, far, simulation);
  expect_refused(out, pw::ERROR_SEAT_OUT_OF_RANGE, DropReason::SeatOutOfRange);
  EXPECT_EQ(out.refusal.text, "seat 3 is out of range: seats are 0 to 2");
  EXPECT_EQ(counts_of(handshake, simulation), before);
  EXPECT_EQ(handshake.seats().seat_of(1), 1u);

  // No seat asked: the lowest free one.
  const HelloDecision lowest = handshake.decide(4, false, hello(), simulation);
  ASSERT_EQ(lowest.outcome, Outcome::Player);
  EXPECT_EQ(lowest.seat, 0u);
}

TEST(HandshakeDecisions, AStragglersSeatStaysTakenUntilItsConnectionCloses) {
  // A straggler's body leaves the world at once (the room has space again) but it
  // keeps its seat until its session closes: the next Hello finds every seat taken.
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(config_with(1));
  ASSERT_EQ(handshake.decide(1, false, hello(), simulation).outcome, Outcome::Player);
  ASSERT_TRUE(simulation.leave(1));
  const HelloDecision decision = handshake.decide(2, false, hello(), simulation);
  expect_refused(decision, pw::ERROR_SERVER_FULL, DropReason::ServerFull);
  EXPECT_EQ(decision.refusal.text, "server full: all 1 seats are taken");
  EXPECT_EQ(handshake.leave(1), Handshake::Member::Player);
  EXPECT_EQ(handshake.decide(3, false, hello(), simulation).outcome, Outcome::Player);
}

TEST(HandshakeDecisions, NoFreeSpawnPositionRefusesThePlayerAndFreesItsSeat) {
  server::Simulation simulation(one_place_scene());
  Handshake handshake(config_with(4));
  ASSERT_EQ(handshake.decide(1, false, hello(), simulation).outcome, Outcome::Player);
  const Counts before = counts_of(handshake, simulation);
  const HelloDecision decision = handshake.decide(2, false, hello(), simulation);
  expect_refused(decision, pw::ERROR_NO_SPAWN, DropReason::NoSpawn);
  EXPECT_EQ(decision.refusal.text, "no free spawn position for another body");
  EXPECT_EQ(counts_of(handshake, simulation), before);
  EXPECT_FALSE(handshake.seats().seat_of(2).has_value());
  // The place frees up when the first player leaves.
  EXPECT_EQ(handshake.leave(1), Handshake::Member::Player);
  ASSERT_TRUE(simulation.leave(1));
  EXPECT_EQ(handshake.decide(3, false, hello(), simulation).outcome, Outcome::Player);
}

TEST(HandshakeDecisions, ChecksRunInTheProtocolsOrder) {
  // PROTOCOL.md 3.1: version, token, view, contact subscription, room, seat, spawn.
  // One Hello wrong on every count is refused for the first; made right one count
  // at a time, it is refused for the next.
  server::Simulation simulation(server_test::free_space_scene());
  server::ServerConfig config = config_with(2);
  config.token = "t";
  Handshake handshake(config);
  pw::Hello good = hello();
  good.set_access_token("t");
  ASSERT_EQ(handshake.decide(1, false, good, simulation).outcome, Outcome::Player);  // seat 0
  ASSERT_EQ(handshake.decide(2, false, good, simulation).outcome, Outcome::Player);  // seat 1

  pw::Hello wrong = hello();
  wrong.set_protocol_version(wire::kProtocolVersion + 1);
  wrong.set_access_token("not t");
  wrong.mutable_view()->set_window(0);
  wrong.mutable_contacts()->set_all(true);
  wrong.set_seat(7);  // out of range, and the room is full

  expect_refused(handshake.decide(3, false, wrong, simulation), pw::ERROR_PROTOCOL_VERSION,
                 DropReason::ProtocolVersion);
  wrong.set_protocol_version(wire::kProtocolVersion);
  expect_refused(handshake.decide(3, false, wrong, simulation), pw::ERROR_BAD_TOKEN,
                 DropReason::BadToken);
  wrong.set_access_token("t");
  expect_refused(handshake.decide(3, false, wrong, simulation), pw::ERROR_INVALID_VIEW,
                 DropReason::InvalidView);
  wrong.clear_view();
  expect_refused(handshake.decide(3, false, wrong, simulation), pw::ERROR_INVALID_SUBSCRIPTION,
                 DropReason::InvalidSubscription);
  wrong.clear_contacts();
  expect_refused(handshake.decide(3, false, wrong, simulation), pw::ERROR_SERVER_FULL,
                 DropReason::ServerFull);
  ASSERT_EQ(handshake.leave(2), Handshake::Member::Player);  // frees seat 1
  ASSERT_TRUE(simulation.leave(2));
  expect_refused(handshake.decide(3, false, wrong, simulation), pw::ERROR_SEAT_OUT_OF_RANGE,
                 DropReason::SeatOutOfRange);
  wrong.set_seat(0);
  expect_refused(handshake.decide(3, false, wrong, simulation), pw::ERROR_SEAT_TAKEN,
                 DropReason::SeatTaken);
  wrong.set_seat(1);
  const HelloDecision welcomed = handshake.decide(3, false, wrong, simulation);
  ASSERT_EQ(welcomed.outcome, Outcome::Player);
  EXPECT_EQ(welcomed.seat, 1u);
}

TEST(HandshakeDecisions, TheSeatIsCheckedBeforeTheSpawn) {
  server::Simulation simulation(one_place_scene());
  Handshake handshake(config_with(2));
  pw::Hello first = hello();
  first.set_seat(0);
  ASSERT_EQ(handshake.decide(1, false, first, simulation).outcome, Outcome::Player);
  // No place left in the world, and seat 0 taken: the seat's error comes first.
  expect_refused(handshake.decide(2, false, first, simulation), pw::ERROR_SEAT_TAKEN,
                 DropReason::SeatTaken);
  pw::Hello free_seat = hello();
  free_seat.set_seat(1);
  expect_refused(handshake.decide(2, false, free_seat, simulation), pw::ERROR_NO_SPAWN,
                 DropReason::NoSpawn);
}

TEST(HandshakeDecisions, ASpectatorsSubscriptionIsCheckedBeforeItsRadiusViewAndItsCap) {
  // A radius view is a valid view (checked with the others, before the
  // subscription); that a spectator has no body to be around is a spectator's rule.
  server::Simulation simulation(server_test::free_space_scene());
  Handshake no_watchers(config_with(2, 0));
  pw::Hello watcher = spectator_hello();
  watcher.mutable_view()->set_interest_radius(3.0);
  watcher.mutable_contacts();  // neither all nor body_ids
  expect_refused(no_watchers.decide(3, false, watcher, simulation), pw::ERROR_INVALID_SUBSCRIPTION,
                 DropReason::InvalidSubscription);
  watcher.mutable_contacts()->set_all(true);
  expect_refused(no_watchers.decide(3, false, watcher, simulation), pw::ERROR_INVALID_VIEW,
                 DropReason::InvalidView);
  watcher.clear_view();
  const HelloDecision full = no_watchers.decide(3, false, watcher, simulation);
  expect_refused(full, pw::ERROR_SERVER_FULL, DropReason::ServerFull);
  // The subscription passed its check: the server holds it until the close.
  ASSERT_TRUE(full.contacts.has_value());
  EXPECT_EQ(full.contacts->kind, server::ContactFilter::Kind::All);
}

TEST(HandshakeDecisions, TheLobbyWaitsForEverySeatThenMakesBodiesInSeatOrder) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(lobby_config(3, 4));
  EXPECT_FALSE(handshake.lobby_open());
  pw::Hello last_seat = hello("c");
  last_seat.set_seat(2);
  pw::Hello middle_seat = hello("b");
  middle_seat.set_seat(1);

  const HelloDecision c = handshake.decide(7, false, last_seat, simulation);
  ASSERT_EQ(c.outcome, Outcome::Lobby);
  EXPECT_EQ(c.seat, 2u);
  EXPECT_FALSE(c.lobby_full);
  const HelloDecision a = handshake.decide(8, false, hello("a"), simulation);
  ASSERT_EQ(a.outcome, Outcome::Lobby);
  EXPECT_EQ(a.seat, 0u);
  EXPECT_FALSE(a.lobby_full);
  EXPECT_EQ(simulation.world().body_count(), 0u);  // nobody has a body yet
  EXPECT_EQ(handshake.lobby_size(), 2u);
  EXPECT_FALSE(handshake.lobby_open());

  const HelloDecision b = handshake.decide(9, false, middle_seat, simulation);
  ASSERT_EQ(b.outcome, Outcome::Lobby);
  EXPECT_TRUE(b.lobby_full);

  const server::LobbyOpening opening = handshake.open_lobby(simulation);
  EXPECT_TRUE(handshake.lobby_open());
  EXPECT_EQ(handshake.lobby_size(), 0u);
  EXPECT_TRUE(opening.no_spawn.empty());
  ASSERT_EQ(opening.welcomed.size(), 3u);
  const server::ClientId in_seat_order[] = {8, 9, 7};
  for (std::uint32_t seat = 0; seat < 3; ++seat) {
    const server::LobbyWelcome& welcome = opening.welcomed[seat];
    EXPECT_EQ(welcome.client, in_seat_order[seat]);
    EXPECT_EQ(welcome.seat, seat);
    EXPECT_EQ(simulation.body_of(welcome.client), welcome.body);
    // Each at its seat's spawn point (x = 0, 10, 20).
    EXPECT_EQ(simulation.world().body(welcome.body)->position.x, 10.0 * seat);
  }
}

TEST(HandshakeDecisions, TheLobbyGivesTheSameWorldWhateverOrderPlayersArriveIn) {
  auto run = [](const std::vector<std::pair<server::ClientId, std::uint32_t>>& arrivals) {
    server::Simulation simulation(server_test::free_space_scene());
    Handshake handshake(lobby_config(3, 3));
    bool full = false;
    for (const auto& [client, seat] : arrivals) {
      pw::Hello message = hello();
      message.set_seat(seat);
      full = handshake.decide(client, false, message, simulation).lobby_full;
    }
    EXPECT_TRUE(full);
    const server::LobbyOpening opening = handshake.open_lobby(simulation);
    std::vector<std::uint64_t> bodies_in_seat_order;
    for (const server::LobbyWelcome& welcome : opening.welcomed) {
      bodies_in_seat_order.push_back(welcome.body.packed());
    }
    return std::make_pair(bodies_in_seat_order, simulation.world().state_hash());
  };
  // Client ids go in connection order, as the server hands them out: the same seats
  // held by different ids, arriving in a different order.
  const auto forward = run({{1, 0}, {2, 1}, {3, 2}});
  const auto backward = run({{1, 2}, {2, 1}, {3, 0}});
  EXPECT_EQ(forward.first, backward.first);
  EXPECT_EQ(forward.second, backward.second);
  EXPECT_EQ(forward.first.size(), 3u);
}

TEST(HandshakeDecisions, LobbyPlayersCountAgainstMaxClientsAndLeavingFreesTheSeat) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(lobby_config(2, 2));
  pw::Hello first = hello();
  first.set_seat(1);
  ASSERT_EQ(handshake.decide(1, false, first, simulation).outcome, Outcome::Lobby);
  EXPECT_EQ(handshake.leave(1), Handshake::Member::Lobby);
  EXPECT_EQ(handshake.lobby_size(), 0u);
  EXPECT_FALSE(handshake.seats().seat_of(1).has_value());
  const HelloDecision again = handshake.decide(2, false, first, simulation);
  ASSERT_EQ(again.outcome, Outcome::Lobby);  // seat 1 is free again
  EXPECT_EQ(again.seat, 1u);
  ASSERT_TRUE(handshake.decide(3, false, hello(), simulation).lobby_full);
  handshake.open_lobby(simulation);
  const HelloDecision late = handshake.decide(4, false, hello(), simulation);
  expect_refused(late, pw::ERROR_SERVER_FULL, DropReason::ServerFull);
  EXPECT_EQ(late.refusal.text, "server full: 2 clients connected");
}

TEST(HandshakeDecisions, AfterTheLobbyOpensANewPlayerTakesAFreeSeatAndJoinsAtOnce) {
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(lobby_config(2, 3));
  ASSERT_EQ(handshake.decide(1, false, hello(), simulation).outcome, Outcome::Lobby);
  ASSERT_TRUE(handshake.decide(2, false, hello(), simulation).lobby_full);
  ASSERT_EQ(handshake.open_lobby(simulation).welcomed.size(), 2u);
  // Room under max_clients but both seats held: full by seats.
  const HelloDecision extra = handshake.decide(3, false, hello(), simulation);
  expect_refused(extra, pw::ERROR_SERVER_FULL, DropReason::ServerFull);
  EXPECT_EQ(extra.refusal.text, "server full: all 2 seats are taken");
  ASSERT_EQ(handshake.leave(1), Handshake::Member::Player);
  ASSERT_TRUE(simulation.leave(1));
  const HelloDecision joined = handshake.decide(4, false, hello(), simulation);
  ASSERT_EQ(joined.outcome, Outcome::Player);
  EXPECT_EQ(joined.seat, 0u);
  EXPECT_TRUE(joined.body.is_valid());
}

TEST(HandshakeDecisions, TheLobbyRefusesThoseItHasNoSpawnFor) {
  server::Simulation simulation(one_place_scene());
  Handshake handshake(lobby_config(2, 2));
  pw::Hello second = hello();
  second.set_seat(1);
  ASSERT_EQ(handshake.decide(5, false, second, simulation).outcome, Outcome::Lobby);
  ASSERT_TRUE(handshake.decide(6, false, hello(), simulation).lobby_full);
  const server::LobbyOpening opening = handshake.open_lobby(simulation);
  // Seat 0 is made first and takes the one place.
  ASSERT_EQ(opening.welcomed.size(), 1u);
  EXPECT_EQ(opening.welcomed[0].client, 6u);
  EXPECT_EQ(opening.no_spawn, (std::vector<server::ClientId>{5}));
  EXPECT_FALSE(handshake.seats().seat_of(5).has_value());
  EXPECT_EQ(handshake.leave(5), Handshake::Member::None);  // nothing left to forget
}

TEST(HandshakeDecisions, NamesAreKeptPrintableAndShort) {
  EXPECT_EQ(server::printable_name(std::string("a\nb\x7f\0c", 6)), "a?b??c");
  EXPECT_EQ(server::printable_name(std::string(100, 'x')),
            std::string(server::kMaxClientNameBytes, 'x'));
  server::Simulation simulation(server_test::free_space_scene());
  Handshake handshake(config_with(4));
  const HelloDecision decision = handshake.decide(1, false, hello("ann\tbell"), simulation);
  EXPECT_EQ(decision.name, "ann?bell");
}

TEST(HandshakeDecisions, OnlyAStrangersFailuresCountAgainstItsAddress) {
  for (const DropReason reason :
       {DropReason::MessageTooLarge, DropReason::Malformed, DropReason::ProtocolVersion,
        DropReason::BadToken, DropReason::UnexpectedMessage, DropReason::InvalidView,
        DropReason::InvalidSubscription, DropReason::HandshakeTimeout}) {
    EXPECT_TRUE(server::is_failed_hello(reason)) << server::to_string(reason);
  }
  for (const DropReason reason :
       {DropReason::ServerFull, DropReason::NoSpawn, DropReason::SeatTaken,
        DropReason::SeatOutOfRange, DropReason::ClientBye, DropReason::Disconnected,
        DropReason::ShuttingDown, DropReason::TooManyPending}) {
    EXPECT_FALSE(server::is_failed_hello(reason)) << server::to_string(reason);
  }
}

}  // namespace
