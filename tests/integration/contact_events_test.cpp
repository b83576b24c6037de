// Contact events over the wire (Hello.contacts, Snapshot.contact_events): a player
// hears of its own body's contacts, a spectator of every body's, a client that did
// not subscribe of none; subscriptions a client may not make are refused.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <string>
#include <vector>

#include "harness.h"
#include "test_scenes.h"

namespace itest {
namespace {

using Events = std::vector<client::ContactEvent>;

bool touches(const client::ContactEvent& e, std::uint64_t body) {
  return e.body_a == body || e.body_b == body;
}

// Waits for a snapshot at or after `tick`, gathering every event on the way.
bool gather_until(client::Client& c, std::uint64_t tick, Events& into) {
  return c
      .wait_for_snapshot(5s,
                         [&](const client::Snapshot& s) {
                           into.insert(into.end(), s.contact_events.begin(),
                                       s.contact_events.end());
                           return s.tick >= tick;
                         })
      .has_value();
}

TEST(ContactEventsWire, APlayerAndASpectatorGetTheirEventsANonSubscriberNone) {
  RunningServer server(test_config(), scene::default_scene());
  client::ClientConfig watching = server.exact_client_config("watcher");
  watching.spectate = true;
  watching.contacts = client::ContactSubscription{true, {}};
  client::Client watcher(watching);
  ASSERT_TRUE(watcher.connect(3s)) << watcher.last_error().to_string();
  client::ClientConfig playing = server.exact_client_config("player");
  playing.contacts = client::ContactSubscription{};
  client::Client player(playing);
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  client::Client quiet(server.exact_client_config("quiet"));
  ASSERT_TRUE(quiet.connect(3s)) << quiet.last_error().to_string();
  const std::uint64_t body = player.welcome().body_id;

  // The player's ball (radius 0.5) spawns with its centre 1 m above the floor's top
  // and lands about 0.32 s later.
  Events mine;
  const auto landed = player.wait_for_snapshot(5s, [&](const client::Snapshot& s) {
    mine.insert(mine.end(), s.contact_events.begin(), s.contact_events.end());
    for (const auto& e : s.contact_events) {
      if (!e.end && touches(e, body)) return true;
    }
    return false;
  });
  ASSERT_TRUE(landed.has_value()) << player.last_error().to_string();
  for (const auto& e : mine) EXPECT_TRUE(touches(e, body));
  const client::ContactEvent landing = mine.back();
  EXPECT_GT(landing.closing_speed, 0.0);
  EXPECT_LE(landing.tick, landed->tick);
  EXPECT_GT(landing.tick, player.welcome().current_tick);

  // The spectator got the same event, bit for bit, among every body's.
  Events all;
  ASSERT_TRUE(gather_until(watcher, landed->tick, all));
  bool found = false;
  for (const auto& e : all) found = found || e == landing;
  EXPECT_TRUE(found);
  Events heard;
  ASSERT_TRUE(gather_until(quiet, landed->tick, heard));
  EXPECT_TRUE(heard.empty());
}

client::ServerError refused(const RunningServer& server, bool spectate,
                            client::ContactSubscription contacts) {
  client::ClientConfig config = server.client_config("refused");
  config.spectate = spectate;
  config.contacts = std::move(contacts);
  client::Client c(config);
  EXPECT_FALSE(c.connect(3s));
  return c.last_error().server.value_or(client::ServerError{});
}

TEST(ContactEventsWire, SubscriptionsAClientMayNotMakeAreRefused) {
  RunningServer server(test_config(), scene::default_scene());
  constexpr std::uint32_t kInvalidSubscription = 21;  // ERROR_INVALID_SUBSCRIPTION
  // A player hears of its own body only.
  client::ServerError error = refused(server, false, {true, {}});
  EXPECT_EQ(error.raw_code, kInvalidSubscription);
  EXPECT_EQ(error.code, client::ErrorCode::InvalidSubscription);
  EXPECT_TRUE(error.fatal);
  EXPECT_NE(error.message.find("own body"), std::string::npos) << error.message;
  EXPECT_EQ(refused(server, false, {false, {1}}).raw_code, kInvalidSubscription);
  // A spectator names all or a list, not both nor neither, and at most 64 bodies.
  EXPECT_EQ(refused(server, true, {}).raw_code, kInvalidSubscription);
  EXPECT_EQ(refused(server, true, {true, {1}}).raw_code, kInvalidSubscription);
  std::vector<std::uint64_t> many(65);
  for (std::size_t i = 0; i < many.size(); ++i) many[i] = i;
  error = refused(server, true, {false, many});
  EXPECT_EQ(error.raw_code, kInvalidSubscription);
  EXPECT_NE(error.message.find("at most 64"), std::string::npos) << error.message;
  // 64 are fine, and the server still serves.
  many.pop_back();
  client::ClientConfig listing = server.client_config("listing");
  listing.spectate = true;
  listing.contacts = client::ContactSubscription{false, many};
  client::Client ok(listing);
  EXPECT_TRUE(ok.connect(3s)) << ok.last_error().to_string();
  EXPECT_EQ(check_server_serves(server), "");
}

// physics-client's output lines (stderr merged), and whether it exited 0.
std::vector<std::string> client_lines(const RunningServer& server, const std::string& flags,
                                      bool& ok) {
  const std::string command = std::string(PHYSICS_CLIENT_EXE) + " --port " +
                              std::to_string(server.port()) + " " + flags + " 2>&1";
  std::vector<std::string> lines;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return lines;
  std::string line;
  for (int c = std::fgetc(pipe); c != EOF; c = std::fgetc(pipe)) {
    if (c == '\n') {
      lines.push_back(line);
      line.clear();
    } else {
      line.push_back(static_cast<char>(c));
    }
  }
  const int status = pclose(pipe);
  ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  return lines;
}

std::size_t contact_lines(const std::vector<std::string>& lines, const std::string& kind) {
  std::size_t n = 0;
  for (const auto& line : lines) n += line.rfind("{\"contact\":\"" + kind + "\"", 0) == 0;
  return n;
}

TEST(ContactEventsWire, PhysicsClientPrintsItsBodysContactsWithContacts) {
  RunningServer server(test_config(), scene::default_scene());
  bool ok = false;
  // The client's ball lands about 20 ticks after it joins.
  const auto subscribed = client_lines(server, "--contacts --ticks 60 --json", ok);
  ASSERT_TRUE(ok);
  EXPECT_GE(contact_lines(subscribed, "begin"), 1u);
  const auto plain = client_lines(server, "--ticks 60 --json", ok);
  ASSERT_TRUE(ok);
  EXPECT_EQ(contact_lines(plain, "begin") + contact_lines(plain, "end"), 0u);
  // A player may not list bodies: refused, and said so.
  const auto refused = client_lines(server, "--contact-bodies 1 --ticks 5", ok);
  EXPECT_FALSE(ok);
  bool said = false;
  for (const auto& line : refused) said = said || line.find("own body") != std::string::npos;
  EXPECT_TRUE(said);
}

}  // namespace
}  // namespace itest
