#pragma once
// A server's tick loop without sockets: a Simulation, the snapshot feeds, and for
// each client the reconstruction the client library would hold, fed the very bytes
// a session would write. Every snapshot is checked as it arrives: it applies, and
// the client's view hash equals the server's. Tests then compare the clients with
// the server's mirrors and with the world.
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "server/game_rules.h"
#include "server/simulation.h"
#include "snapshot_feeds.h"
#include "truth_frame.h"
#include "wire/reconstruction.h"

namespace server_test {

struct FakeClient {
  server::FeedClient id = 0;
  wire::ViewSettings settings;
  wire::Reconstruction held;
  bool acks = true;  // acknowledge each snapshot at once
  std::uint64_t snapshots = 0;
  std::uint64_t records = 0;
  std::uint64_t bytes = 0;                            // framed, as on the wire
  std::map<std::uint64_t, std::uint64_t> records_of;  // sends per body id
  std::vector<physics::wire::Snapshot> log;           // when keep_log
  bool keep_log = false;
  std::uint64_t last_tick = 0;
  std::uint32_t since_hash = 0;  // snapshots since the last that carried a view hash
};

class FeedRun {
 public:
  explicit FeedRun(scene::SceneDef scene, bool lockstep = false, std::uint64_t heartbeat = 60,
                   std::shared_ptr<server::GameRules> rules = nullptr);

  // Joins a client with these settings (its body from the scene's spawn points).
  FakeClient& join(const wire::ViewSettings& settings);
  // Joins a spectator with these settings: no body.
  FakeClient& spectate(const wire::ViewSettings& settings);
  void leave(server::FeedClient id);
  // One tick: inputs (set through `sim()` first), step, feed every client.
  void tick();
  void ticks(int n) {
    for (int i = 0; i < n; ++i) tick();
  }

  server::Simulation& sim() { return sim_; }
  server::SnapshotFeeds& feeds() { return feeds_; }
  const server::TruthFrame& frame() const { return frame_; }
  FakeClient& client(server::FeedClient id) { return clients_.at(id); }
  wire::Predictor predictor() const { return predictor_; }

  // The largest |client - world| per axis over the bodies `c` holds, advanced to now:
  // positions and velocities separately.
  std::pair<double, double> worst_error(const FakeClient& c) const;
  // True when the client holds exactly the server's mirror of it.
  bool holds_mirror(const FakeClient& c) const;

 private:
  server::Simulation sim_;
  wire::Predictor predictor_;
  server::SnapshotFeeds feeds_;
  server::TruthFrame frame_;
  std::map<server::FeedClient, FakeClient> clients_;
  server::FeedClient next_id_ = 1;
};

// The scenes of scenes/ by name ("moving-1000", "large-4000", ...).
scene::SceneDef scene_file(const std::string& name);

}  // namespace server_test
