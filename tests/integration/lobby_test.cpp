// The lockstep lobby and seats: a scripted run gives the same hashes at every tick
// whatever order the players' connections land in; taken and out-of-range seats
// are refused; a straggler is dropped after --lockstep-max-timeouts; a clamped
// input is said once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "harness.h"

namespace itest {
namespace {

constexpr std::uint32_t kPlayers = 3;
constexpr std::uint64_t kTicks = 40;

// The input of the player in `seat` at `tick`: the script depends on the seat only.
client::Vec2 seat_input(std::uint32_t seat, std::uint64_t tick) {
  const double phase = static_cast<double>(tick) * 0.3 + static_cast<double>(seat) * 2.1;
  return {(3.0 + static_cast<double>(seat)) * std::cos(phase), 4.0 * std::sin(phase) + 8.0};
}

struct SeatRun {
  std::uint64_t body_id = 0;
  std::vector<std::uint64_t> hashes;  // tick 1..kTicks
  std::string failure;
};

// One fresh server with a lobby of kPlayers; the players connect in `order` (seat
// numbers), each after its own delay, from threads of their own.
std::vector<SeatRun> run_lobby(const std::vector<std::uint32_t>& order,
                               const std::vector<std::chrono::milliseconds>& delays,
                               server::ServerConfig::Pace pace = server::ServerConfig::Pace::Asap) {
  server::ServerConfig config = test_config(/*lockstep=*/true);
  config.lockstep_pace = pace;
  config.lockstep_players = static_cast<int>(kPlayers);
  config.lockstep_timeout = 10s;  // every tick waits for every input
  RunningServer server(config, scene::default_scene());
  std::vector<SeatRun> runs(kPlayers);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::uint32_t seat = order[i];
    threads.emplace_back([&, seat, delay = delays[i]] {
      std::this_thread::sleep_for(delay);  // how connections land: the point of the test
      client::ClientConfig cc = server.exact_client_config("seat-" + std::to_string(seat));
      cc.seat = seat;
      client::Client player(cc);
      SeatRun& run = runs[seat];
      if (!player.connect(10s)) {
        run.failure = player.last_error().to_string();
        return;
      }
      if (player.welcome().seat != seat || player.welcome().seats != kPlayers ||
          player.welcome().current_tick != 0) {
        run.failure = "welcome: seat " + std::to_string(player.welcome().seat) + " of " +
                      std::to_string(player.welcome().seats) + " at tick " +
                      std::to_string(player.welcome().current_tick);
        return;
      }
      run.body_id = player.welcome().body_id;
      for (std::uint64_t tick = 1; tick <= kTicks; ++tick) {
        const client::Vec2 a = seat_input(seat, tick);
        player.send_input(tick, a.x, a.y);
        const auto snapshot = player.next_snapshot(10s);
        if (!snapshot || snapshot->tick != tick) {
          run.failure = "no snapshot of tick " + std::to_string(tick) + ": " +
                        player.last_error().to_string();
          return;
        }
        run.hashes.push_back(snapshot->state_hash);
      }
      player.disconnect();
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(server.stats().lockstep_timeouts, 0u);
  return runs;
}

TEST(Lobby, ThreePlayersGiveTheSameHashesAtEveryTickWhateverTheConnectOrder) {
  const std::vector<SeatRun> first = run_lobby({0, 1, 2}, {0ms, 40ms, 80ms});
  const std::vector<SeatRun> second = run_lobby({2, 0, 1}, {0ms, 60ms, 20ms});
  for (std::uint32_t seat = 0; seat < kPlayers; ++seat) {
    ASSERT_EQ(first[seat].failure, "") << "first run, seat " << seat;
    ASSERT_EQ(second[seat].failure, "") << "second run, seat " << seat;
    ASSERT_EQ(first[seat].hashes.size(), kTicks);
    // The seat, not the race, decides the body.
    EXPECT_EQ(first[seat].body_id, second[seat].body_id) << "seat " << seat;
    // Every player saw the same world, and both runs the same, tick by tick.
    EXPECT_EQ(first[seat].hashes, first[0].hashes) << "seat " << seat;
    for (std::uint64_t i = 0; i < kTicks; ++i) {
      ASSERT_EQ(first[seat].hashes[i], second[seat].hashes[i])
          << "seat " << seat << " tick " << i + 1;
    }
  }
  // Bodies are made in seat order.
  EXPECT_LT(first[0].body_id, first[1].body_id);
  EXPECT_LT(first[1].body_id, first[2].body_id);
  // The inputs moved the world: the hashes are not one constant.
  EXPECT_NE(first[0].hashes.front(), first[0].hashes.back());
}

TEST(Lobby, RealtimePaceStepsTheSameWorldAsAsap) {
  const std::vector<SeatRun> asap = run_lobby({1, 2, 0}, {0ms, 10ms, 20ms});
  const std::vector<SeatRun> paced =
      run_lobby({0, 2, 1}, {0ms, 10ms, 20ms}, server::ServerConfig::Pace::Realtime);
  for (std::uint32_t seat = 0; seat < kPlayers; ++seat) {
    ASSERT_EQ(asap[seat].failure, "") << "seat " << seat;
    ASSERT_EQ(paced[seat].failure, "") << "seat " << seat;
    EXPECT_EQ(asap[seat].hashes, paced[seat].hashes) << "seat " << seat;
  }
}

physics::wire::ClientMessage seated_hello(const std::string& name, std::uint32_t seat) {
  physics::wire::ClientMessage hello = hello_message(name);
  hello.mutable_hello()->set_seat(seat);
  return hello;
}

TEST(Lobby, NobodyIsWelcomedNorAnyTickSteppedUntilEverySeatIsTaken) {
  server::ServerConfig config = test_config(/*lockstep=*/true);
  config.lockstep_players = 2;
  RunningServer server(config, scene::default_scene());
  RawPeer late_seat(server.port());
  ASSERT_TRUE(late_seat.send(seated_hello("one", 1)));
  late_seat.send(input_message(1, 1.0, 0.0));  // not in the world yet: ignored
  EXPECT_FALSE(late_seat.receive(200ms).has_value());
  ASSERT_TRUE(eventually([&] { return server.stats().lobby_clients == 1; }));
  EXPECT_EQ(server.stats().connected_clients, 0u);
  EXPECT_EQ(server.stats().current_tick, 0u);

  RawPeer early_seat(server.port());
  ASSERT_TRUE(early_seat.send(seated_hello("zero", 0)));
  const auto zero = early_seat.receive(3s);
  const auto one = late_seat.receive(3s);
  ASSERT_TRUE(zero && zero->has_welcome());
  ASSERT_TRUE(one && one->has_welcome());
  EXPECT_EQ(zero->welcome().seat(), 0u);
  EXPECT_EQ(one->welcome().seat(), 1u);
  EXPECT_EQ(zero->welcome().seats(), 2u);
  EXPECT_EQ(zero->welcome().current_tick(), 0u);
  EXPECT_EQ(one->welcome().current_tick(), 0u);
  // Seat 0's body was made first though it connected last; both Welcomes list both.
  EXPECT_LT(zero->welcome().body_id(), one->welcome().body_id());
  EXPECT_EQ(zero->welcome().bodies_size(), one->welcome().bodies_size());
  EXPECT_EQ(server.stats().connected_clients, 2u);
  EXPECT_EQ(server.stats().lobby_clients, 0u);
}

TEST(Seats, ATakenSeatIsRefusedInTheLobbyAndAfterIt) {
  server::ServerConfig config = test_config(/*lockstep=*/true);
  config.lockstep_players = 2;
  RunningServer server(config, scene::default_scene());
  RawPeer holder(server.port());
  ASSERT_TRUE(holder.send(seated_hello("holder", 1)));
  ASSERT_TRUE(eventually([&] { return server.stats().lobby_clients == 1; }));

  client::ClientConfig cc = server.client_config("same-seat");
  cc.seat = 1;
  client::Client rival(cc);
  EXPECT_FALSE(rival.connect(3s));
  EXPECT_EQ(rival.state(), client::ConnectionState::Refused);
  ASSERT_TRUE(rival.last_error().server.has_value());
  EXPECT_EQ(rival.last_error().server->code, client::ErrorCode::SeatTaken);
  EXPECT_TRUE(
      eventually([&] { return dropped(server.stats(), server::DropReason::SeatTaken) == 1u; }));
  // The holder kept its seat and is still waiting.
  EXPECT_EQ(server.stats().lobby_clients, 1u);
}

TEST(Seats, AnOutOfRangeSeatIsRefusedAndNamesTheRange) {
  server::ServerConfig config = test_config();
  config.max_clients = 4;  // no lobby: the seats are the player slots
  RunningServer server(config, scene::default_scene());
  client::ClientConfig cc = server.client_config("far");
  cc.seat = 4;
  client::Client far(cc);
  EXPECT_FALSE(far.connect(3s));
  ASSERT_TRUE(far.last_error().server.has_value());
  EXPECT_EQ(far.last_error().server->code, client::ErrorCode::SeatOutOfRange);
  EXPECT_NE(far.last_error().server->message.find("0 to 3"), std::string::npos)
      << far.last_error().server->message;

  cc.seat = 3;
  client::Client last(cc);
  ASSERT_TRUE(last.connect(3s)) << last.last_error().to_string();
  EXPECT_EQ(last.welcome().seat, 3u);
  EXPECT_EQ(last.welcome().seats, 4u);
  client::Client unseated(server.client_config("any"));
  ASSERT_TRUE(unseated.connect(3s));
  EXPECT_EQ(unseated.welcome().seat, 0u);  // the lowest free seat
}

TEST(Lockstep, AStragglerIsDroppedAfterMaxTimeoutsAndTheOthersGoOnWithoutWaiting) {
  server::ServerConfig config = test_config(/*lockstep=*/true);
  config.lockstep_timeout = 20ms;
  config.lockstep_max_timeouts = 3;
  RunningServer server(config, scene::default_scene());
  client::Client eager(server.client_config("eager"));
  RawPeer stopped(server.port());
  ASSERT_TRUE(eager.connect(3s));
  ASSERT_TRUE(stopped.send(hello_message("stopped")));
  ASSERT_TRUE(stopped.receive(3s).has_value());  // its Welcome; then it sends nothing
  ASSERT_TRUE(eventually([&] { return server.stats().connected_clients == 2; }));
  // No tick steps while nobody sends an input, however many timeouts pass.
  EXPECT_FALSE(eager.next_snapshot(100ms).has_value());
  EXPECT_EQ(server.stats().current_tick, 0u);
  EXPECT_EQ(server.stats().lockstep_timeouts, 0u);
  constexpr std::uint64_t kEagerTicks = 6;
  for (std::uint64_t tick = 1; tick <= kEagerTicks; ++tick) eager.send_input(tick, 1.0, 0.0);
  // In lockstep every tick stepped is sent, in order.
  for (std::uint64_t tick = 1; tick <= kEagerTicks; ++tick) {
    const auto snapshot = eager.next_snapshot(5s);
    ASSERT_TRUE(snapshot.has_value()) << "tick " << tick << ": " << eager.last_error().to_string();
    EXPECT_EQ(snapshot->tick, tick);
  }
  const auto error = stopped.receive_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code(), physics::wire::ERROR_LOCKSTEP_STRAGGLER);
  EXPECT_TRUE(error->fatal());
  EXPECT_TRUE(stopped.wait_closed(3s));
  EXPECT_TRUE(eventually(
      [&] { return dropped(server.stats(), server::DropReason::LockstepStraggler) == 1u; }));
  // Ticks 1 to 3 waited for the straggler and were stepped with its held input; from
  // tick 4 on nobody waited.
  EXPECT_EQ(server.stats().lockstep_timeouts, 3u);
  EXPECT_EQ(server.stats().reused_inputs, 3u);
  EXPECT_EQ(server.stats().connected_clients, 1u);
}

TEST(Inputs, AClampedAccelerationIsSaidOnceToThatClient) {
  const scene::SceneDef scene = scene::default_scene();
  RunningServer server(test_config(), scene);
  client::Client pusher(server.client_config("pusher"));
  ASSERT_TRUE(pusher.connect(3s));
  EXPECT_EQ(pusher.welcome().max_acceleration, scene.max_acceleration);
  const double over = 10.0 * scene.max_acceleration;
  const std::uint64_t start = pusher.welcome().current_tick + 5;
  for (std::uint64_t i = 0; i < 3; ++i) pusher.send_input(start + i, over, 0.0);
  const auto error = pusher.next_error(3s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code, client::ErrorCode::InputClamped);
  EXPECT_FALSE(error->fatal);
  EXPECT_TRUE(eventually([&] { return server.stats().clamped_inputs == 3u; }));
  EXPECT_FALSE(pusher.next_error(300ms).has_value());  // once, not once an input
  EXPECT_EQ(pusher.state(), client::ConnectionState::Connected);
}

}  // namespace
}  // namespace itest
