#pragma once
// Goal rush's rules: two players, one ball, a goal at each end (sensors), a moving
// platform (kinematic), shots that never hit their own player (collision groups),
// and two game messages, "jump" and "shoot". The server calls them at fixed points of
// every tick (server/game_rules.h); everything they decide depends only on the
// world, the inputs and the messages, so every run is reproducible and replayable.
// What they keep between ticks (the seats, the ways the players face, the scores,
// the shots and when each expires) is in the world's game state, not in members:
// a saved world, a replay, a resync and a late joiner's world hold it, and the
// state hash covers it (physics_testing::check_rules_state_in_world checks this).
//
// Messages from a player: "jump" (an upward impulse, when its body rests on
// something), "shoot" (a shot flies from its body the way it last steered) and "zap"
// (an instant shot: a ray cast from its body the way it last steered, kZapRange long,
// that stops at the first solid body other than the player and its shots; the ball,
// if that is what it meets, is knocked on by kZapImpulse). The zapper is told what
// the zap met: "zap ball", "zap player", "zap blocked" (the ground, a wall, the
// ceiling, the platform or a body the rules made) or "zap nothing".
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
inline constexpr double kZapRange = 40.0;   // m
inline constexpr double kZapImpulse = 4.0;  // N s, along the zap

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
  void on_timer(server::GameWorld& world, std::string_view name, std::uint64_t index) override;

  // What a world of the game holds (a server's, a test's, or one a client was sent).
  static int score(const phys::World& world, Side side);
  // The side a player plays, if it is in the game.
  static std::optional<Side> side_of(const phys::World& world, server::ClientId client);
  static std::size_t shots_in_flight(const phys::World& world);

  // Where the ball is put back after a goal.
  static constexpr phys::Vec2 kBallStart{0.0, 8.0};

 private:
  // A player's seat, as the game state holds it.
  struct Seat {
    Side side = Side::Left;
    double facing = 1.0;  // +1 right, -1 left: the way its shots fly
  };

  static std::optional<Seat> seat_of(const server::GameWorld& world, server::ClientId client);
  // A body of the scene by its name (on_create checked that each is there).
  static phys::BodyId scene_body(const server::GameWorld& world, std::string_view name);
  void move_platform(server::GameWorld& world);
  void jump(server::GameWorld& world, server::ClientId client);
  void shoot(server::GameWorld& world, server::ClientId client);
  void zap(server::GameWorld& world, server::ClientId client);
  void score_goal(server::GameWorld& world, Side scorer);

  phys::BodyDef player_;  // configuration, the same in every tick
};

}  // namespace goal_rush
