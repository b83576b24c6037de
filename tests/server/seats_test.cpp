// Seats: asked-for seats, the lowest free one otherwise, taken and out-of-range
// seats refused; a seat puts the body at its own spawn point.
#include "seats.h"

#include <gtest/gtest.h>

#include "server/simulation.h"
#include "test_scene.h"

namespace {

using server::SeatTable;
using Outcome = SeatTable::Outcome;

TEST(Seats, AskedSeatIsGivenAndOthersGetTheLowestFree) {
  SeatTable seats(3);
  EXPECT_EQ(seats.claim(10, 2).outcome, Outcome::Seated);
  const SeatTable::Claim first = seats.claim(11, std::nullopt);
  EXPECT_EQ(first.outcome, Outcome::Seated);
  EXPECT_EQ(first.seat, 0u);
  EXPECT_EQ(seats.claim(12, std::nullopt).seat, 1u);
  EXPECT_TRUE(seats.full());
  EXPECT_EQ(seats.claim(13, std::nullopt).outcome, Outcome::Full);
  // Seat order, not claim order.
  EXPECT_EQ(seats.in_seat_order(), (std::vector<server::ClientId>{11, 12, 10}));
}

TEST(Seats, TakenAndOutOfRangeSeatsAreRefusedAndChangeNothing) {
  SeatTable seats(2);
  ASSERT_EQ(seats.claim(1, 1).outcome, Outcome::Seated);
  const SeatTable::Claim taken = seats.claim(2, 1);
  EXPECT_EQ(taken.outcome, Outcome::Taken);
  EXPECT_EQ(taken.seat, 1u);
  EXPECT_EQ(seats.claim(2, 2).outcome, Outcome::OutOfRange);
  EXPECT_EQ(seats.claim(2, 4000000000u).outcome, Outcome::OutOfRange);
  EXPECT_EQ(seats.taken(), 1u);
  EXPECT_FALSE(seats.seat_of(2).has_value());
  EXPECT_EQ(seats.seat_of(1), 1u);
}

TEST(Seats, ReleasedSeatIsFreeAgainAndASeatedClientKeepsItsSeat) {
  SeatTable seats(2);
  ASSERT_EQ(seats.claim(1, std::nullopt).seat, 0u);
  EXPECT_EQ(seats.claim(1, 1).seat, 0u);  // already seated: keeps seat 0
  EXPECT_TRUE(seats.release(1));
  EXPECT_FALSE(seats.release(1));
  EXPECT_EQ(seats.claim(2, 0).outcome, Outcome::Seated);
}

TEST(Seats, ASeatPutsTheBodyAtItsOwnSpawnPointWhateverJoinedBefore) {
  // free_space_scene: spawn points at x = 0, 10, 20.
  server::Simulation simulation(server_test::free_space_scene());
  const auto late = simulation.join(5, 2u);
  const auto early = simulation.join(6, 0u);
  const auto plain = simulation.join(7);  // no seat: the first free point
  ASSERT_TRUE(late && early && plain);
  EXPECT_EQ(simulation.world().body(*late)->position.x, 20.0);
  EXPECT_EQ(simulation.world().body(*early)->position.x, 0.0);
  EXPECT_EQ(simulation.world().body(*plain)->position.x, 10.0);
}

TEST(Seats, ASeatWhosePointIsTakenFallsBackToTheFirstFreePosition) {
  server::Simulation simulation(server_test::free_space_scene());
  ASSERT_TRUE(simulation.join(1));             // at x = 0
  const auto seated = simulation.join(2, 3u);  // seat 3 mod 3 points: x = 0, taken
  ASSERT_TRUE(seated);
  EXPECT_EQ(simulation.world().body(*seated)->position.x, 10.0);
}

}  // namespace
