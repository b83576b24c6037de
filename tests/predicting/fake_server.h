#pragma once
// A stand-in for physics-server's input relay, in-process: a phys::World built
// from a scene, stepped with scripted inputs, joins and leaves, each tick handed out
// as the RelayTick the server would send (changes made before the inputs, inputs
// only when they differ from the last one relayed, the state hash every
// hash_interval ticks).
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "client/types.h"
#include "physics/world.h"
#include "scene/scene.h"
#include "wire.pb.h"

namespace predicting_test {

class FakeServer {
 public:
  // The default scene with `players` player bodies at its spawn points.
  explicit FakeServer(int players = 2, std::uint32_t hash_interval = 1);

  std::uint64_t tick() const { return tick_; }
  double tick_rate() const { return tick_rate_; }
  // The scene's input limit: inputs are clamped to it, as the server's input check does.
  double max_acceleration() const { return max_acceleration_; }
  std::uint64_t player(int index) const { return players_.at(static_cast<std::size_t>(index)); }
  const phys::World& world() const { return world_; }
  // A copy of the world now (what Welcome.world_state carries).
  phys::World copy() const { return phys::World(world_.save()); }
  // The state hash after each tick stepped.
  const std::map<std::uint64_t, std::uint64_t>& hashes() const { return hashes_; }

  // The acceleration `body` gets from `tick` on (held), as a client's Input: clamped
  // to max_acceleration().
  void input(std::uint64_t body, std::uint64_t tick, client::Vec2 a);
  // A body added, or removed, before the inputs of the next tick stepped.
  std::uint64_t join_next_tick(const phys::BodyDef& def);
  void leave_next_tick(std::uint64_t body);
  // Steps one tick; returns it as relayed.
  physics::wire::RelayTick step();
  // The player body definition of the scene, at a free spot.
  phys::BodyDef player_def(double x) const;

 private:
  phys::World world_;
  double tick_rate_ = 60.0;
  double max_acceleration_ = 0.0;
  double dt_ = 0.0;
  std::uint32_t hash_interval_ = 1;
  std::uint64_t tick_ = 0;
  std::vector<std::uint64_t> players_;
  phys::BodyDef player_;
  // Scheduled inputs: body -> tick -> acceleration.
  std::map<std::uint64_t, std::map<std::uint64_t, client::Vec2>> inputs_;
  std::map<std::uint64_t, client::Vec2> relayed_;  // the last acceleration relayed, by body
  std::vector<phys::BodyDef> joins_;
  std::vector<std::uint64_t> leaves_;
  std::map<std::uint64_t, std::uint64_t> hashes_;
};

// A snapshot carrying these relayed ticks (its tick the newest's), as the thin
// client hands it over.
client::Snapshot relay_snapshot(const std::vector<physics::wire::RelayTick>& ticks);

}  // namespace predicting_test
