// Networked runs recorded by a real server replay in-process with every tick's hash
// equal: in lockstep with three clients, and at a fixed rate with late inputs, a
// client joining mid-run and one leaving.
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <vector>

#include "harness.h"
#include "replay_support.h"
#include "replayer.h"
#include "wire.pb.h"

namespace {

using namespace std::chrono_literals;
using Kind = physics::recording::Record::KindCase;

// Steps the whole recording; every tick must carry a recorded hash equal to the
// replay's and, where a client saw the tick, to the hash the client was sent.
void expect_replays_exactly(const std::filesystem::path& path,
                            const std::map<std::uint64_t, std::uint64_t>& seen,
                            std::uint64_t at_least_ticks) {
  auto opened = replay::Replayer::open(path);
  ASSERT_TRUE(std::holds_alternative<std::unique_ptr<replay::Replayer>>(opened))
      << std::get<recording::RecordingError>(opened).to_string();
  replay::Replayer& replayer = *std::get<std::unique_ptr<replay::Replayer>>(opened);
  std::uint64_t ticks = 0;
  std::size_t compared_with_clients = 0;
  for (;;) {
    const replay::Replayer::Step step = replayer.step();
    ASSERT_NE(step, replay::Replayer::Step::BadFile) << replayer.error().to_string();
    if (step == replay::Replayer::Step::End) break;
    const replay::TickCheck& check = replayer.last_check();
    ++ticks;
    ASSERT_EQ(check.tick, ticks);
    ASSERT_TRUE(check.hash_recorded) << "tick " << check.tick;
    ASSERT_EQ(check.replayed_hash, check.recorded_hash) << "tick " << check.tick;
    ASSERT_TRUE(check.join_mismatches.empty()) << check.join_mismatches.front();
    ASSERT_TRUE(check.bodies.empty()) << "tick " << check.tick;
    if (const auto it = seen.find(check.tick); it != seen.end()) {
      ASSERT_EQ(check.replayed_hash, it->second) << "tick " << check.tick;
      ++compared_with_clients;
    }
  }
  EXPECT_GE(ticks, at_least_ticks);
  EXPECT_EQ(compared_with_clients, seen.size());

  const replay::ReplayReport report = replay::check_recording_file(path);
  EXPECT_EQ(report.outcome, replay::ReplayReport::Outcome::Equal) << report.error.to_string();
  EXPECT_EQ(report.ticks, ticks);
  EXPECT_EQ(report.hashes_checked, ticks);
}

TEST(NetworkedReplay, LockstepRunOfThreeClientsReplaysWithEveryTickHashEqual) {
  rtest::TempFile file("lockstep.rec");
  constexpr std::size_t kClients = 3;
  constexpr std::uint64_t kTicks = 150;
  std::map<std::uint64_t, std::uint64_t> seen;
  std::size_t expected_inputs = 0;
  {
    server::ServerConfig config = itest::test_config(/*lockstep=*/true);
    config.lockstep_timeout = 10s;  // every tick waits for every input
    config.record_path = file.path().string();
    itest::RunningServer server(config, scene::default_scene());
    std::vector<std::unique_ptr<client::Client>> players;
    for (std::size_t k = 0; k < kClients; ++k) {
      players.push_back(std::make_unique<client::Client>(
          server.exact_client_config("lockstep-" + std::to_string(k))));
      ASSERT_TRUE(players.back()->connect(3s)) << players.back()->last_error().to_string();
    }
    const std::uint64_t start = players.front()->welcome().current_tick;
    for (std::uint64_t tick = start + 1; tick <= start + kTicks; ++tick) {
      for (std::size_t k = 0; k < kClients; ++k) {
        const phys::Vec2 a = rtest::scripted_input(k, tick);
        ASSERT_TRUE(players[k]->send_input(tick, a.x, a.y));
        if (tick == start + 1 || !(rtest::scripted_input(k, tick - 1) == a)) ++expected_inputs;
      }
      for (std::size_t k = 0; k < kClients; ++k) {
        auto snapshot = players[k]->next_snapshot(5s);
        ASSERT_TRUE(snapshot.has_value()) << players[k]->last_error().to_string();
        ASSERT_EQ(snapshot->tick, tick);
        if (k == 0) seen[tick] = snapshot->state_hash;
        ASSERT_EQ(snapshot->state_hash, seen[tick]) << "client " << k;
      }
    }
    EXPECT_EQ(server.stats().reused_inputs, 0u);
  }  // the server stops: the recording is complete

  const recording::LoadedRecording loaded = rtest::load_or_fail(file.path());
  ASSERT_TRUE(loaded.header.has_server());
  EXPECT_TRUE(loaded.header.server().lockstep());
  EXPECT_EQ(rtest::count_kind(loaded, Kind::kJoin), kClients);
  // Only the inputs that changed a body's acceleration: one in five here.
  EXPECT_EQ(rtest::count_kind(loaded, Kind::kInput), expected_inputs);
  EXPECT_LT(expected_inputs, kClients * kTicks / 4);
  expect_replays_exactly(file.path(), seen, kTicks);
}

TEST(NetworkedReplay, FixedRateRunWithLateInputsAndAMidRunJoinReplaysExactly) {
  rtest::TempFile file("fixed-rate.rec");
  std::map<std::uint64_t, std::uint64_t> seen;
  std::uint64_t late_inputs = 0;
  std::uint64_t joined_mid_run_at = 0;
  {
    server::ServerConfig config = itest::test_config(/*lockstep=*/false);
    config.record_path = file.path().string();
    itest::RunningServer server(config, scene::default_scene());
    client::Client a(server.exact_client_config("a"));
    client::Client b(server.exact_client_config("b"));
    ASSERT_TRUE(a.connect(3s)) << a.last_error().to_string();
    ASSERT_TRUE(b.connect(3s)) << b.last_error().to_string();
    std::unique_ptr<client::Client> c;
    for (int i = 0; i < 90; ++i) {
      auto snapshot = a.next_snapshot(5s);
      ASSERT_TRUE(snapshot.has_value()) << a.last_error().to_string();
      seen[snapshot->tick] = snapshot->state_hash;
      const std::uint64_t t = snapshot->tick;
      // a names a tick already stepped (late: applied at the next one); b and c
      // name ticks ahead.
      const phys::Vec2 ia = rtest::scripted_input(0, t, 3);
      ASSERT_TRUE(a.send_input(t, ia.x, ia.y));
      if (i < 60) {
        const phys::Vec2 ib = rtest::scripted_input(1, t, 4);
        ASSERT_TRUE(b.send_input(t + 2, ib.x, ib.y));
      } else if (i == 60) {
        b.disconnect("leaving mid-run");
      }
      if (i == 30) {
        c = std::make_unique<client::Client>(server.exact_client_config("c"));
        ASSERT_TRUE(c->connect(3s)) << c->last_error().to_string();
        joined_mid_run_at = c->welcome().current_tick;
      }
      if (c) {
        const phys::Vec2 ic = rtest::scripted_input(2, t, 2);
        ASSERT_TRUE(c->send_input(t + 1, ic.x, ic.y));
        (void)c->newest_snapshot(0ms);  // keeps its window open
      }
      (void)b.newest_snapshot(0ms);
    }
    ASSERT_TRUE(itest::eventually([&] { return server.stats().late_inputs > 0; }));
    late_inputs = server.stats().late_inputs;
  }
  EXPECT_GT(late_inputs, 0u);
  EXPECT_GT(joined_mid_run_at, 0u);

  const recording::LoadedRecording loaded = rtest::load_or_fail(file.path());
  EXPECT_FALSE(loaded.header.server().lockstep());
  EXPECT_EQ(rtest::count_kind(loaded, Kind::kJoin), 3u);
  EXPECT_GE(rtest::count_kind(loaded, Kind::kLeave), 1u);
  bool found_mid_run_join = false;
  for (const auto& record : loaded.records) {
    if (record.has_join() && record.join().tick() == joined_mid_run_at) found_mid_run_join = true;
  }
  EXPECT_TRUE(found_mid_run_join);
  ASSERT_GE(seen.size(), 80u);
  expect_replays_exactly(file.path(), seen, seen.rbegin()->first);
}

// physics-client --record (the client library's record_path): every message the
// client received, in order, with its exact bytes.
TEST(ClientRecording, HoldsEveryMessageReceivedInOrder) {
  rtest::TempFile file("client.rec");
  std::vector<std::uint64_t> ticks;
  std::uint64_t snapshots_received = 0;
  {
    itest::RunningServer server(itest::test_config(true), scene::default_scene());
    client::ClientConfig config = server.exact_client_config("recorded");
    config.record_path = file.path().string();
    client::Client player(config);
    ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
    for (std::uint64_t t = player.welcome().current_tick + 1; ticks.size() < 20; ++t) {
      ASSERT_TRUE(player.send_input(t, 1.0, 0.0));
      auto snapshot = player.next_snapshot(5s);
      ASSERT_TRUE(snapshot.has_value());
      ticks.push_back(snapshot->tick);
    }
    snapshots_received = player.stats().snapshots_received;
    player.disconnect();
  }
  const recording::LoadedRecording loaded = rtest::load_or_fail(file.path());
  ASSERT_TRUE(loaded.header.has_client());
  EXPECT_EQ(loaded.header.client().name(), "recorded");
  ASSERT_GE(loaded.records.size(), 1 + snapshots_received);
  std::vector<std::uint64_t> recorded_ticks;
  std::uint64_t previous_micros = 0;
  for (std::size_t i = 0; i < loaded.records.size(); ++i) {
    ASSERT_TRUE(loaded.records[i].has_received());
    const auto& received = loaded.records[i].received();
    EXPECT_GE(received.micros(), previous_micros);
    previous_micros = received.micros();
    physics::wire::ServerMessage message;
    ASSERT_TRUE(message.ParseFromString(received.server_message()));
    if (i == 0) {
      EXPECT_TRUE(message.has_welcome());
    } else if (message.has_snapshot()) {
      recorded_ticks.push_back(message.snapshot().tick());
    }
  }
  ASSERT_GE(recorded_ticks.size(), ticks.size());
  recorded_ticks.resize(ticks.size());
  EXPECT_EQ(recorded_ticks, ticks);
}

}  // namespace
