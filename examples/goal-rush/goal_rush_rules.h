#pragma once
// Goal rush's rules: two players, one ball, a goal at each end (sensors), a moving
// platform (kinematic), shots that never hit their own player (collision groups),
// and two game messages, "jump" and "shoot". The server calls them at fixed points of
// every tick (server/game_rules.h); everything they decide depends only on the
// world, the inputs and the messages, so every run is reproducible and replayable.
//
// Messages from a player: "jump" (an upward impulse, when its body rests on
// something) and "shoot" (a shot flies from its body the way it last steered).
// Messages to the players: "score L R" after each goal, "win left" or "win right"
// when a side reaches kWinningScore (the scores then start again from 0).
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "physics/body.h"
#include "server/game_rules.h"

namespace goal_rush {

inline constexpr int kWinningScore = 5;
inline constexpr double kPlatformSpeed = 2.0;     // m/s
inline constexpr double kPlatformHalfPath = 6.0;  // m each side of x = 0
inline constexpr double kJumpSpeed = 7.0;         // m/s upward
inline constexpr double kShotSpeed = 14.0;        // m/s
inline constexpr std::uint64_t kShotLifeTicks = 90;
inline constexpr std::size_t kMaxShotsPerPlayer = 3;

enum class Side : std::uint8_t { Left, Right };

class GoalRushRules : public server::GameRules {
 public:
  // `player`: the body each player gets (the scene's player definition).
  explicit GoalRushRules(phys::BodyDef player);

  void on_create(server::GameWorld& world) override;
  server::JoinDecision on_join(server::GameWorld& world, server::ClientId client,
                               std::optional<std::uint32_t> seat) override;
  void on_leave(server::GameWorld& world, server::ClientId client) override;
  void before_step(server::GameWorld& world,
                   const std::vector<server::AppliedInput>& inputs) override;
  void after_step(server::GameWorld& world) override;

  int score(Side side) const { return score_[static_cast<std::size_t>(side)]; }
  // The side a player plays, if it is in the game.
  std::optional<Side> side_of(server::ClientId client) const;
  std::size_t shots_in_flight() const { return shots_.size(); }

  // Where the ball is put back after a goal.
  static constexpr phys::Vec2 kBallStart{0.0, 8.0};

 private:
  struct Seat {
    std::optional<server::ClientId> client;
    double facing = 1.0;  // +1 right, -1 left: the way its shots fly
  };
  struct Shot {
    phys::BodyId body;
    server::ClientId owner = 0;
    std::uint64_t expires = 0;  // the tick it is removed at
  };

  Seat* seat_of(server::ClientId client);
  void move_platform(server::GameWorld& world);
  void jump(server::GameWorld& world, server::ClientId client);
  void shoot(server::GameWorld& world, server::ClientId client);
  void score_goal(server::GameWorld& world, Side scorer);
  void expire_shots(server::GameWorld& world);

  phys::BodyDef player_;
  std::array<Seat, 2> seats_{};
  std::array<int, 2> score_{};
  std::vector<Shot> shots_;
  phys::BodyId ball_;
  phys::BodyId platform_;
  phys::BodyId left_goal_;
  phys::BodyId right_goal_;
};

}  // namespace goal_rush
