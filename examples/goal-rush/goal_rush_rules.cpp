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

}  // namespace

GoalRushRules::GoalRushRules(phys::BodyDef player) : player_(std::move(player)) {}

void GoalRushRules::on_create(server::GameWorld& world) {
  const auto need = [&world](std::string_view name) {
    const std::optional<phys::BodyId> id = world.find_body(name);
    if (!id)
      throw std::runtime_error("goal rush: the scene has no body named " + std::string(name));
    return *id;
  };
  ball_ = need("ball");
  platform_ = need("platform");
  left_goal_ = need("left goal");
  right_goal_ = need("right goal");
}

GoalRushRules::Seat* GoalRushRules::seat_of(server::ClientId client) {
  for (Seat& seat : seats_) {
    if (seat.client == client) return &seat;
  }
  return nullptr;
}

std::optional<Side> GoalRushRules::side_of(server::ClientId client) const {
  for (std::size_t i = 0; i < seats_.size(); ++i) {
    if (seats_[i].client == client) return static_cast<Side>(i);
  }
  return std::nullopt;
}

server::JoinDecision GoalRushRules::on_join(server::GameWorld& /*world*/, server::ClientId client,
                                            std::optional<std::uint32_t> /*seat*/) {
  server::JoinDecision decision;
  const auto free =
      std::find_if(seats_.begin(), seats_.end(), [](const Seat& seat) { return !seat.client; });
  if (free == seats_.end()) {
    decision.refuse = "the game is full: two players";
    return decision;
  }
  const auto index = static_cast<std::size_t>(free - seats_.begin());
  free->client = client;
  free->facing = index == 0 ? 1.0 : -1.0;  // each starts facing the other's goal
  phys::BodyDef body = player_;
  body.position = kSpawn[index];
  // A negative group of its own: the player and its shots never meet.
  body.filter.group = -static_cast<std::int32_t>(client);
  body.name = index == 0 ? "left player" : "right player";
  decision.body = body;
  return decision;
}

void GoalRushRules::on_leave(server::GameWorld& world, server::ClientId client) {
  if (Seat* seat = seat_of(client)) seat->client.reset();
  // Its shots go with it.
  std::erase_if(shots_, [&world, client](const Shot& shot) {
    if (shot.owner != client) return false;
    world.destroy(shot.body);
    return true;
  });
}

void GoalRushRules::before_step(server::GameWorld& world,
                                const std::vector<server::AppliedInput>& inputs) {
  move_platform(world);
  expire_shots(world);
  for (const server::AppliedInput& input : inputs) {
    if (Seat* seat = seat_of(input.client); seat && input.acceleration.x != 0.0) {
      seat->facing = input.acceleration.x > 0.0 ? 1.0 : -1.0;
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
  }
}

void GoalRushRules::after_step(server::GameWorld& world) {
  for (const phys::SensorEvent& event : world.sensor_events()) {
    if (event.kind != phys::SensorEventKind::Begin || event.visitor != ball_) continue;
    if (event.sensor == left_goal_) score_goal(world, Side::Right);
    if (event.sensor == right_goal_) score_goal(world, Side::Left);
  }
}

// The platform runs between x = -kPlatformHalfPath and +kPlatformHalfPath, turning
// at each end: a path kept by the rules, not by the physics.
void GoalRushRules::move_platform(server::GameWorld& world) {
  const std::optional<phys::BodyState> platform = world.body(platform_);
  if (!platform) return;
  const double x = platform->position.x;
  const double vx = platform->velocity.x;
  if (x >= kPlatformHalfPath && vx > 0.0) world.set_velocity(platform_, {-kPlatformSpeed, 0.0});
  if (x <= -kPlatformHalfPath && vx < 0.0) world.set_velocity(platform_, {kPlatformSpeed, 0.0});
}

void GoalRushRules::jump(server::GameWorld& world, server::ClientId client) {
  const std::optional<phys::BodyId> id = world.body_of(client);
  if (!id) return;
  const std::optional<phys::BodyState> body = world.body(*id);
  if (!body || !resting(*body)) return;
  world.set_velocity(*id, {body->velocity.x, kJumpSpeed});
}

void GoalRushRules::shoot(server::GameWorld& world, server::ClientId client) {
  const Seat* seat = seat_of(client);
  const std::optional<phys::BodyId> id = world.body_of(client);
  if (seat == nullptr || !id) return;
  const auto owned = std::count_if(shots_.begin(), shots_.end(),
                                   [client](const Shot& shot) { return shot.owner == client; });
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
  if (made.is_valid()) shots_.push_back({made, client, world.tick() + kShotLifeTicks});
}

void GoalRushRules::score_goal(server::GameWorld& world, Side scorer) {
  int& points = score_[static_cast<std::size_t>(scorer)];
  ++points;
  world.broadcast("score " + std::to_string(score_[0]) + " " + std::to_string(score_[1]));
  if (points >= kWinningScore) {
    world.broadcast(scorer == Side::Left ? "win left" : "win right");
    score_ = {};
  }
  world.set_position(ball_, kBallStart);
  world.set_velocity(ball_, {0.0, 0.0});
}

void GoalRushRules::expire_shots(server::GameWorld& world) {
  std::erase_if(shots_, [&world](const Shot& shot) {
    if (world.tick() < shot.expires) return false;
    world.destroy(shot.body);
    return true;
  });
}

}  // namespace goal_rush
