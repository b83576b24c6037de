#include "goal_rush_rules.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace goal_rush {

namespace {

constexpr std::array<phys::Vec2, 2> kSpawn{{{-8.0, 1.0}, {8.0, 1.0}}};

// A body rests on something when it barely moves up or down: the jump needs a floor.
bool resting(const phys::BodyState& body) { return std::abs(body.velocity.y) < 0.05; }

// The game state's names. Per side (index 0 left, 1 right): the player in the seat,
// the way it faces (a number), its score. Per shot (index: its body id): its owner,
// and the timer that removes it.
constexpr std::string_view kSeat = "seat";
constexpr std::string_view kFacing = "facing";
constexpr std::string_view kScore = "score";
constexpr std::string_view kShot = "shot";

std::uint64_t index_of(Side side) { return static_cast<std::uint64_t>(side); }

// The shots in flight, as (body id, owner), in body id order.
std::vector<std::pair<std::uint64_t, std::int64_t>> shots(const phys::GameState& state) {
  std::vector<std::pair<std::uint64_t, std::int64_t>> found;
  const auto& ints = state.ints();
  for (auto it = ints.lower_bound(phys::GameState::KeyView{kShot, 0});
       it != ints.end() && it->first.name == kShot; ++it) {
    found.emplace_back(it->first.index, it->second);
  }
  return found;
}

}  // namespace

GoalRushRules::GoalRushRules(phys::BodyDef player) : player_(std::move(player)) {}

void GoalRushRules::on_create(server::GameWorld& world) {
  for (const std::string_view name : {"ball", "platform", "left goal", "right goal"}) {
    if (!world.find_body(name)) {
      throw std::runtime_error("goal rush: the scene has no body named " + std::string(name));
    }
  }
}

phys::BodyId GoalRushRules::scene_body(const server::GameWorld& world, std::string_view name) {
  return world.find_body(name).value_or(phys::BodyId::invalid());
}

std::optional<GoalRushRules::Seat> GoalRushRules::seat_of(const server::GameWorld& world,
                                                          server::ClientId client) {
  for (const Side side : {Side::Left, Side::Right}) {
    if (world.get_int(kSeat, index_of(side)) == static_cast<std::int64_t>(client)) {
      return Seat{side, world.get_number(kFacing, index_of(side), 1.0)};
    }
  }
  return std::nullopt;
}

int GoalRushRules::score(const phys::World& world, Side side) {
  return static_cast<int>(world.game_state().get_int(kScore, index_of(side)).value_or(0));
}

std::optional<Side> GoalRushRules::side_of(const phys::World& world, server::ClientId client) {
  for (const Side side : {Side::Left, Side::Right}) {
    if (world.game_state().get_int(kSeat, index_of(side)) == static_cast<std::int64_t>(client)) {
      return side;
    }
  }
  return std::nullopt;
}

std::size_t GoalRushRules::shots_in_flight(const phys::World& world) {
  return shots(world.game_state()).size();
}

server::JoinDecision GoalRushRules::on_join(server::GameWorld& world, server::ClientId client,
                                            std::optional<std::uint32_t> /*seat*/) {
  server::JoinDecision decision;
  const bool left_free = world.get_int(kSeat, index_of(Side::Left)) == 0;
  if (!left_free && world.get_int(kSeat, index_of(Side::Right)) != 0) {
    decision.refuse = "the game is full: two players";
    return decision;
  }
  const std::size_t index = left_free ? 0 : 1;
  world.set_int(kSeat, static_cast<std::int64_t>(client), index);
  world.set_number(kFacing, index == 0 ? 1.0 : -1.0, index);  // facing the other's goal
  phys::BodyDef body = player_;
  body.position = kSpawn[index];
  // A negative group of its own: the player and its shots never meet.
  body.filter.group = -static_cast<std::int32_t>(client);
  body.name = index == 0 ? "left player" : "right player";
  decision.body = body;
  return decision;
}

void GoalRushRules::on_leave(server::GameWorld& world, server::ClientId client) {
  if (const std::optional<Seat> seat = seat_of(world, client)) {
    world.erase(kSeat, index_of(seat->side));
    world.erase(kFacing, index_of(seat->side));
  }
  // Its shots go with it.
  for (const auto& [shot, owner] : shots(world.game_state())) {
    if (owner != static_cast<std::int64_t>(client)) continue;
    world.destroy(phys::BodyId::from_packed(shot));
    world.erase(kShot, shot);
    world.cancel_timer(kShot, shot);
  }
}

// A shot's time is up: it goes.
void GoalRushRules::on_timer(server::GameWorld& world, std::string_view name, std::uint64_t index) {
  if (name != kShot) return;
  world.destroy(phys::BodyId::from_packed(index));
  world.erase(kShot, index);
}

void GoalRushRules::before_step(server::GameWorld& world,
                                const std::vector<server::AppliedInput>& inputs) {
  move_platform(world);
  for (const server::AppliedInput& input : inputs) {
    const std::optional<Seat> seat = seat_of(world, input.client);
    if (seat && input.acceleration.x != 0.0) {
      world.set_number(kFacing, input.acceleration.x > 0.0 ? 1.0 : -1.0, index_of(seat->side));
    }
  }
  // Players run left and right; up and down are the jump's and gravity's. Every
  // tick, for every player: a client that sends the same input again has it set
  // again before this call, though it is listed in `inputs` only when it changes.
  for (const auto& [client, body] : world.players()) {
    const std::optional<phys::BodyState> state = world.body(body);
    if (state && state->acceleration.y != 0.0) {
      world.set_acceleration(body, {state->acceleration.x, 0.0});
    }
  }
  for (const server::ClientGameMessage& message : world.messages()) {
    if (message.payload == "jump") jump(world, message.client);
    if (message.payload == "shoot") shoot(world, message.client);
    if (message.payload == "zap") zap(world, message.client);
  }
}

void GoalRushRules::after_step(server::GameWorld& world) {
  const phys::BodyId ball = scene_body(world, "ball");
  const phys::BodyId left_goal = scene_body(world, "left goal");
  const phys::BodyId right_goal = scene_body(world, "right goal");
  for (const phys::SensorEvent& event : world.sensor_events()) {
    if (event.kind != phys::SensorEventKind::Begin || event.visitor != ball) continue;
    if (event.sensor == left_goal) score_goal(world, Side::Right);
    if (event.sensor == right_goal) score_goal(world, Side::Left);
  }
}

// The platform runs between x = -kPlatformHalfPath and +kPlatformHalfPath, turning
// at each end: a path kept by the rules, not by the physics.
void GoalRushRules::move_platform(server::GameWorld& world) {
  const phys::BodyId id = scene_body(world, "platform");
  const std::optional<phys::BodyState> platform = world.body(id);
  if (!platform) return;
  const double x = platform->position.x;
  const double vx = platform->velocity.x;
  if (x >= kPlatformHalfPath && vx > 0.0) world.set_velocity(id, {-kPlatformSpeed, 0.0});
  if (x <= -kPlatformHalfPath && vx < 0.0) world.set_velocity(id, {kPlatformSpeed, 0.0});
}

void GoalRushRules::jump(server::GameWorld& world, server::ClientId client) {
  const std::optional<phys::BodyId> id = world.body_of(client);
  if (!id) return;
  const std::optional<phys::BodyState> body = world.body(*id);
  if (!body || !resting(*body)) return;
  world.set_velocity(*id, {body->velocity.x, kJumpSpeed});
}

void GoalRushRules::shoot(server::GameWorld& world, server::ClientId client) {
  const std::optional<Seat> seat = seat_of(world, client);
  const std::optional<phys::BodyId> id = world.body_of(client);
  if (!seat || !id) return;
  const auto in_flight = shots(world.game_state());
  const auto owned = std::count_if(in_flight.begin(), in_flight.end(), [client](const auto& shot) {
    return shot.second == static_cast<std::int64_t>(client);
  });
  if (static_cast<std::size_t>(owned) >= kMaxShotsPerPlayer) return;
  const std::optional<phys::BodyState> body = world.body(*id);
  if (!body) return;
  // The shot starts inside its player: their shared group keeps them apart.
  phys::BodyDef shot;
  shot.shape = phys::Shape::Circle;
  shot.radius = 0.15;
  shot.mass = 0.3;
  shot.restitution = 0.5;
  shot.position = body->position;
  shot.velocity = {seat->facing * kShotSpeed, 2.0};
  shot.filter.group = -static_cast<std::int32_t>(client);
  shot.name = "shot";
  const phys::BodyId made = world.create(shot);
  if (!made.is_valid()) return;
  world.set_int(kShot, static_cast<std::int64_t>(client), made.packed());
  world.start_timer(kShot, kShotLifeTicks, 0, made.packed());
}

// A ray from the player's centre: its own group filters out the player and its shots,
// and the goals, sensors, are skipped as every query skips them by default.
void GoalRushRules::zap(server::GameWorld& world, server::ClientId client) {
  const std::optional<Seat> seat = seat_of(world, client);
  const std::optional<phys::BodyId> id = world.body_of(client);
  if (!seat || !id) return;
  const std::optional<phys::BodyState> body = world.body(*id);
  if (!body) return;
  phys::QueryFilter not_own;
  not_own.filter = phys::Filter{};
  not_own.filter->group = -static_cast<std::int32_t>(client);
  const std::optional<phys::CastHit> hit =
      world.cast_ray(body->position, {seat->facing * kZapRange, 0.0}, not_own);
  if (!hit) {
    world.send(client, "zap nothing");
  } else if (hit->body == scene_body(world, "ball")) {
    world.apply_impulse(hit->body, {seat->facing * kZapImpulse, 0.0});
    world.send(client, "zap ball");
  } else {
    const bool player =
        std::any_of(world.players().begin(), world.players().end(),
                    [&hit](const auto& entry) { return entry.second == hit->body; });
    world.send(client, player ? "zap player" : "zap blocked");
  }
}

void GoalRushRules::score_goal(server::GameWorld& world, Side scorer) {
  const std::int64_t points = world.get_int(kScore, index_of(scorer)) + 1;
  world.set_int(kScore, points, index_of(scorer));
  world.broadcast("score " + std::to_string(world.get_int(kScore, index_of(Side::Left))) + " " +
                  std::to_string(world.get_int(kScore, index_of(Side::Right))));
  if (points >= kWinningScore) {
    world.broadcast(scorer == Side::Left ? "win left" : "win right");
    world.erase(kScore, index_of(Side::Left));
    world.erase(kScore, index_of(Side::Right));
  }
  const phys::BodyId ball = scene_body(world, "ball");
  world.set_position(ball, kBallStart);
  world.set_velocity(ball, {0.0, 0.0});
}

}  // namespace goal_rush
