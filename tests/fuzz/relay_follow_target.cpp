#include "relay_follow_target.h"

#include <google/protobuf/io/coded_stream.h>

#include <cstdlib>
#include <optional>

#include "client/prediction_core.h"
#include "relay/follow_relay.h"
#include "scene/scene.h"
#include "wire.pb.h"

namespace relay_fuzz {
namespace {

// The default scene with two players, as a server builds it before its first tick.
struct Start {
  phys::World world;
  std::uint64_t player = 0;
  double dt = 0.0;
  double tick_rate = 0.0;
};

Start start_world() {
  const scene::SceneDef& scene = scene::default_scene();
  Start start{scene::build_world(scene), 0, scene::fixed_dt(scene), scene.tick_rate};
  for (std::size_t i = 0; i < 2; ++i) {
    phys::BodyDef def = scene.player;
    def.position = scene.spawn_points.at(i % scene.spawn_points.size());
    const phys::BodyId id = start.world.add_body(def);
    if (i == 0) start.player = id.packed();
  }
  return start;
}

// Reads the length-delimited RelayTicks after byte 0; stops at the first that does
// not parse or is cut short (what came before is still used).
std::vector<std::string> read_ticks(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> ticks;
  google::protobuf::io::CodedInputStream in(data, static_cast<int>(size));
  std::uint32_t length = 0;
  while (ticks.size() < 512 && in.ReadVarint32(&length)) {
    std::string bytes;
    if (length > 1u << 16 || !in.ReadString(&bytes, static_cast<int>(length))) break;
    ticks.push_back(std::move(bytes));
  }
  return ticks;
}

void follow_each(const std::vector<std::string>& ticks, const Start& start) {
  phys::World world(start.world.save());
  physics::wire::RelayTick tick;
  for (const std::string& bytes : ticks) {
    if (!tick.ParseFromString(bytes)) continue;
    const relay::FollowResult result = relay::follow(world, tick, start.dt);
    // A world left part-way must be replaced, as a client replaces it with the
    // server's world_state.
    if (result.problem == relay::FollowProblem::BodyMismatch ||
        result.problem == relay::FollowProblem::BadInput) {
      world = phys::World(start.world.save());
    }
  }
}

void predict_through(const std::vector<std::string>& ticks, const Start& start, bool player,
                     std::size_t per_snapshot) {
  client::PredictionConfig config;
  config.max_rollback = 8;
  client::PredictionCore core(config);
  core.start(phys::World(start.world.save()), 0, player ? start.player : 0, start.tick_rate, 50.0);
  std::uint64_t confirmed = core.confirmed_tick();
  for (std::size_t i = 0; i < ticks.size(); i += per_snapshot) {
    client::Snapshot snapshot;
    for (std::size_t k = i; k < ticks.size() && k < i + per_snapshot; ++k) {
      snapshot.relay.push_back(ticks[k]);
    }
    snapshot.tick = confirmed + snapshot.relay.size();
    const std::uint64_t ahead = core.predicted_tick() + 2;
    if (player) core.set_input(ahead, {static_cast<double>(i % 7) - 3.0, 1.0});
    core.advance_to(ahead);
    core.on_snapshot(snapshot);
    (void)core.take_full_state_request();
    if (core.failed()) return;
    if (core.confirmed_tick() < confirmed) std::abort();
    confirmed = core.confirmed_tick();
    if (core.predicted_tick() < confirmed && !core.awaiting_full_state()) std::abort();
    if (core.predicted_tick() > confirmed + config.max_rollback) std::abort();
    (void)core.render();
  }
}

}  // namespace

void run_one(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return;
  static const Start start = start_world();
  const std::vector<std::string> ticks = read_ticks(data + 1, size - 1);
  follow_each(ticks, start);
  predict_through(ticks, start, (data[0] & 1) != 0, 1 + ((data[0] >> 1) & 3));
}

std::vector<std::string> make_seeds() {
  Start start = start_world();
  const scene::SceneDef& scene = scene::default_scene();
  phys::World world(start.world.save());
  std::string relayed;  // the length-delimited ticks so far
  std::vector<std::string> seeds;
  phys::BodyId joined;
  for (std::uint64_t t = 1; t <= 40; ++t) {
    physics::wire::RelayTick tick;
    tick.set_tick(t);
    if (t == 10) {
      phys::BodyDef def = scene.player;
      def.position = {-5.0, 20.0};
      joined = world.add_body(def);
      physics::wire::RelayBody& body = *tick.add_changes()->mutable_added();
      body.set_body_id(joined.packed());
      body.set_shape(def.shape == phys::Shape::Circle ? physics::wire::SHAPE_CIRCLE
                                                      : physics::wire::SHAPE_BOX);
      body.set_radius(def.radius);
      body.mutable_half_extents()->set_x(def.half_extents.x);
      body.mutable_half_extents()->set_y(def.half_extents.y);
      body.mutable_position()->set_x(def.position.x);
      body.mutable_position()->set_y(def.position.y);
      body.set_mass(def.mass);
      body.set_restitution(def.restitution);
      body.mutable_friction()->set_x(def.friction.x);
      body.mutable_friction()->set_y(def.friction.y);
      body.set_contact_friction(def.contact_friction);
    }
    if (t == 30) {
      world.remove_body(joined);
      tick.add_changes()->set_removed(joined.packed());
    }
    if (t % 5 == 1) {
      const phys::Vec2 a{static_cast<double>(t % 3) * 4.0 - 4.0, 2.0};
      world.set_acceleration(phys::BodyId::from_packed(start.player), a);
      physics::wire::RelayInput& input = *tick.add_inputs();
      input.set_body_id(start.player);
      input.set_ax(a.x);
      input.set_ay(a.y);
    }
    world.step(start.dt);
    if (t % 4 == 0) tick.set_state_hash(world.state_hash());
    const std::string bytes = tick.SerializeAsString();
    for (std::size_t n = bytes.size();; n >>= 7) {  // the varint byte count
      relayed.push_back(static_cast<char>((n & 0x7F) | (n > 0x7F ? 0x80 : 0)));
      if (n <= 0x7F) break;
    }
    relayed += bytes;
    if (t == 12 || t == 40) {
      for (const char first : {'\x01', '\x00', '\x05'}) seeds.push_back(first + relayed);
    }
  }
  return seeds;
}

}  // namespace relay_fuzz
