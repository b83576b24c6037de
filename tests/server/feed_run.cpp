#include "feed_run.h"

#include <algorithm>
#include <cmath>

#include "snapshot_encoder.h"
#include "wire/framing.h"

namespace server_test {

FeedRun::FeedRun(scene::SceneDef scene, bool lockstep, std::uint64_t heartbeat)
    : sim_(std::move(scene)),
      predictor_(sim_.tick_rate(), sim_.world().settings().gravity.x,
                 sim_.world().settings().gravity.y),
      feeds_(predictor_, heartbeat, lockstep) {}

FakeClient& FeedRun::join(const wire::ViewSettings& settings) {
  const server::FeedClient id = next_id_++;
  const auto body = sim_.join(id);
  EXPECT_TRUE(body.has_value()) << "no spawn point for client " << id;
  feeds_.join(id, settings, body ? std::optional<std::uint64_t>(body->packed()) : std::nullopt);
  FakeClient& c = clients_[id];
  c.id = id;
  c.settings = settings;
  return c;
}

void FeedRun::leave(server::FeedClient id) {
  sim_.leave(id);
  feeds_.leave(id);
  clients_.erase(id);
}

void FeedRun::tick() {
  const server::TickResult result = sim_.step_tick();
  const server::BodyChanges changes = sim_.take_changes();
  for (const phys::BodyId id : changes.added) feeds_.note_added(id.packed());
  for (const std::uint64_t id : changes.removed) feeds_.note_removed(id);
  server::TruthFrame frame = server::read_truth(sim_.world(), result.tick, &frame_);
  frame_ = std::move(frame);
  const auto outputs = feeds_.after_tick(frame_, sim_.world(), [&](server::FeedClient client) {
    server::ClientFields fields;
    if (const server::ClientInputs* in = sim_.inputs_of(client)) {
      fields.last_applied_input_tick = in->last_applied_tick();
      fields.has_applied_input = in->has_applied();
    }
    return fields;
  });
  for (const server::FeedOutput& out : outputs) {
    FakeClient& c = clients_.at(out.client);
    // Exactly the bytes a session writes: header, the view's part, the client's own.
    const std::string bytes = server::snapshot_frame_header(out.shared->size() + out.tail.size()) +
                              *out.shared + out.tail;
    wire::FrameReader reader;
    reader.feed({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()});
    std::string payload;
    ASSERT_EQ(reader.next(payload), wire::FrameStatus::Frame);
    physics::wire::ServerMessage message;
    ASSERT_TRUE(message.ParseFromString(payload));
    ASSERT_TRUE(message.has_snapshot());
    const physics::wire::Snapshot& snapshot = message.snapshot();
    ASSERT_EQ(snapshot.tick(), result.tick);
    if (c.settings.encoding != physics::wire::ENCODING_FULL) {
      ASSERT_EQ(c.held.apply(snapshot, predictor_, c.settings.quantum), "");
      ASSERT_EQ(c.held.hash(), snapshot.view_hash())
          << "client " << c.id << " tick " << result.tick;
      std::vector<std::uint64_t> ids;
      ASSERT_TRUE(wire::decode_id_gaps(snapshot.quantized().id_gaps(), ids));
      for (const auto id : ids) ++c.records_of[id];
      ASSERT_TRUE(wire::decode_id_gaps(snapshot.exact().id_gaps(), ids));
      for (const auto id : ids) ++c.records_of[id];
      ASSERT_TRUE(wire::decode_id_gaps(snapshot.velocities().id_gaps(), ids));
      for (const auto id : ids) ++c.records_of[id];
    }
    ++c.snapshots;
    c.records += out.records;
    c.bytes += bytes.size();
    c.last_tick = snapshot.tick();
    if (c.keep_log) c.log.push_back(snapshot);
    if (c.acks) {
      EXPECT_EQ(feeds_.ack(c.id, snapshot.tick()), server::AckResult::Accepted);
    }
  }
}

std::pair<double, double> FeedRun::worst_error(const FakeClient& c) const {
  wire::Reconstruction now = c.held;
  now.advance_to(frame_.tick, predictor_);
  double position = 0.0;
  double velocity = 0.0;
  for (const wire::PredictedBody& b : now.bodies()) {
    const server::TruthBody* t = frame_.find(b.id);
    if (t == nullptr) continue;
    position = std::max({position, std::fabs(t->x - b.x), std::fabs(t->y - b.y)});
    velocity = std::max({velocity, std::fabs(t->vx - b.vx), std::fabs(t->vy - b.vy)});
  }
  return {position, velocity};
}

bool FeedRun::holds_mirror(const FakeClient& c) const {
  const server::View* view = feeds_.view_of(c.id);
  if (view == nullptr) return false;
  wire::Reconstruction now = c.held;
  now.advance_to(view->mirror().tick(), predictor_);
  const auto& a = now.bodies();
  const auto& b = view->mirror().bodies();
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].id != b[i].id ||
        std::bit_cast<std::uint64_t>(a[i].x) != std::bit_cast<std::uint64_t>(b[i].x) ||
        std::bit_cast<std::uint64_t>(a[i].y) != std::bit_cast<std::uint64_t>(b[i].y) ||
        std::bit_cast<std::uint64_t>(a[i].vx) != std::bit_cast<std::uint64_t>(b[i].vx) ||
        std::bit_cast<std::uint64_t>(a[i].vy) != std::bit_cast<std::uint64_t>(b[i].vy) ||
        a[i].mode != b[i].mode) {
      return false;
    }
  }
  return true;
}

scene::SceneDef scene_file(const std::string& name) {
  auto loaded = scene::load_scene_file(std::string(PHYSICS_SCENES_DIR) + "/" + name + ".textproto");
  if (auto* error = std::get_if<scene::SceneError>(&loaded)) {
    ADD_FAILURE() << error->to_string();
    return {};
  }
  return std::get<scene::SceneDef>(std::move(loaded));
}

}  // namespace server_test
