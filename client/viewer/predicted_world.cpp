#include "predicted_world.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

namespace viewer {
namespace {

client::PredictingClientConfig predicting(client::ClientConfig config,
                                          std::shared_ptr<server::GameRules> rules) {
  client::PredictingClientConfig out;
  out.rules = std::move(rules);
  // A player: a spectator's prediction is the confirmed world, nothing of its own.
  config.spectate = false;
  // The world's state in the Welcome: about 300 bytes a body.
  config.max_message_bytes = std::max<std::size_t>(config.max_message_bytes, std::size_t{64} << 20);
  out.client = std::move(config);
  return out;
}

client::BodyShape shape_of(const phys::World& world, const phys::BodyState& body) {
  client::BodyShape shape;
  shape.body_id = body.id.packed();
  shape.shape =
      body.shape == phys::Shape::Circle ? client::ShapeType::Circle : client::ShapeType::Box;
  shape.radius = body.radius;
  shape.half_extents = {body.half_extents.x, body.half_extents.y};
  shape.is_static = body.motion == phys::Motion::Static;
  shape.is_kinematic = body.motion == phys::Motion::Kinematic;
  shape.position = {body.position.x, body.position.y};
  shape.mass = body.mass;
  shape.restitution = body.restitution;
  shape.friction = {body.friction.x, body.friction.y};
  shape.is_sensor = world.is_sensor(body.id);
  shape.name = std::string(world.name(body.id));
  return shape;
}

}  // namespace

PredictedWorld::PredictedWorld(client::ClientConfig config,
                               std::shared_ptr<server::GameRules> rules)
    : client_(predicting(std::move(config), std::move(rules))) {}

bool PredictedWorld::connect(std::chrono::milliseconds timeout) {
  if (!client_.connect(timeout)) {
    ended_ = true;
    return false;
  }
  shapes_.reset(client_.welcome().bodies);
  learn_shapes();
  return true;
}

void PredictedWorld::pump(std::chrono::steady_clock::time_point until) {
  const auto send = [this](std::uint64_t tick, const std::string& payload) {
    return client_.send_game_message(tick, payload);
  };
  const auto hold_still = [&](std::uint64_t tick) {
    messages_.send_queued(send, tick);
    return client::Vec2{};
  };
  while (!ended_) {
    const client::PollResult polled = client_.poll(until, hold_still);
    if (polled == client::PollResult::Ended) ended_ = true;
    if (polled == client::PollResult::Deadline) break;
  }
  messages_.received(client_.connection().take_game_messages());
}

bool PredictedWorld::send_game_message(std::string payload) {
  messages_.queue(std::move(payload));
  return true;
}

void PredictedWorld::learn_shapes() {
  const phys::World& world = client_.core().predicted_world();
  if (shapes_.all().size() == world.body_count()) return;
  std::vector<client::BodyShape> known = shapes_.list();
  world.for_each_body([&](const phys::BodyState& body) {
    if (shapes_.find(body.id.packed()) == nullptr) known.push_back(shape_of(world, body));
  });
  shapes_.reset(known);
}

const client::PlayoutFrame& PredictedWorld::frame() {
  learn_shapes();
  const client::RenderState shown = client_.render();
  frame_.status = client::PlayoutStatus::Interpolating;
  frame_.server_time = static_cast<double>(shown.tick) / client_.welcome().tick_rate;
  frame_.newest_tick = client_.core().confirmed_tick();
  frame_.lag = 0.0;
  frame_.extrapolated = 0.0;
  frame_.bodies.clear();
  frame_.bodies.reserve(shown.bodies.size());
  for (const client::RenderBody& body : shown.bodies) {
    client::PlayoutBody& drawn = frame_.bodies.emplace_back();
    drawn.body_id = body.body_id;
    drawn.position = body.position;
    drawn.velocity = body.velocity;
  }
  return frame_;
}

const client::PlayoutFrame& PredictedWorld::update(double /*now*/) {
  pump(std::chrono::steady_clock::now() + std::chrono::milliseconds(1));
  return frame();
}

std::vector<std::string> PredictedWorld::panel(const client::PlayoutFrame& shown,
                                               std::optional<std::uint64_t> followed) const {
  const client::Welcome& welcome = client_.welcome();
  const client::PredictionCore& core = client_.core();
  const client::PredictionStats& stats = core.stats();
  std::vector<std::string> lines;
  lines.push_back(fmt::format("scene '{}'  {:g} ticks/s  predicting, own body {}",
                              welcome.scene_name, welcome.tick_rate, core.own_body()));
  lines.push_back(
      fmt::format("tick {} predicted, {} confirmed", core.predicted_tick(), core.confirmed_tick()));
  lines.push_back(fmt::format(
      "rollbacks {}  re-simulated {}  largest correction {:.3f} m  desyncs {}", stats.rollbacks,
      stats.resimulated_ticks, stats.largest_correction, stats.desyncs));
  lines.push_back(shapes_.bodies_line(shown, followed));
  for (std::string& line : messages_.panel_lines()) lines.push_back(std::move(line));
  // The rules' messages of the ticks not confirmed yet, as this client predicts them;
  // the server's replace them once it has stepped those ticks.
  if (core.runs_rules()) {
    const std::vector<server::OutgoingGameMessage> predicted = core.predicted_messages();
    const std::size_t first =
        predicted.size() > GameMessages::kShown ? predicted.size() - GameMessages::kShown : 0;
    for (std::size_t i = first; i < predicted.size(); ++i) {
      lines.push_back(fmt::format("  tick {} (predicted): {}", predicted[i].tick,
                                  predicted[i].payload.substr(0, 60)));
    }
  }
  if (ended_) lines.push_back("disconnected: " + error());
  return lines;
}

}  // namespace viewer
