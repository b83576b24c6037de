#include "feed_run.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "snapshot_encoder.h"
#include "wire/framing.h"

namespace server_test {
namespace {

// A quantised value rounds (true - held) / quantum to the nearest integer, so the
// client ends within half a quantum of the world, give or take the rounding of the
// doubles on the way (a few ulps of the values themselves).
void expect_within_half_a_quantum(double held, double truth, double quantum, const char* what,
                                  std::uint64_t id) {
  const double ulps = 8.0 * std::numeric_limits<double>::epsilon() *
                      std::max({1.0, std::fabs(held), std::fabs(truth)});
  ASSERT_LE(std::fabs(held - truth), 0.5 * quantum + ulps)
      << what << " of body " << id << ": held " << held << ", world " << truth;
}

// Every body of a quantised or velocity record, as the client holds it after the
// snapshot, against the world on the axes the record carried.
void check_rounding(const physics::wire::Snapshot& snapshot, const wire::Reconstruction& held,
                    const server::TruthFrame& frame, wire::Quantum q) {
  std::vector<std::uint64_t> exact_ids;
  ASSERT_TRUE(wire::decode_id_gaps(snapshot.exact().id_gaps(), exact_ids));
  const auto sent_exact = [&](std::uint64_t id) {
    return std::find(exact_ids.begin(), exact_ids.end(), id) != exact_ids.end();
  };
  const auto check = [&](const google::protobuf::RepeatedField<std::uint64_t>& gaps,
                         bool positions) {
    std::vector<std::uint64_t> ids;
    ASSERT_TRUE(wire::decode_id_gaps(gaps, ids));
    for (const std::uint64_t id : ids) {
      if (sent_exact(id)) continue;
      const wire::PredictedBody* b = held.find(id);
      const server::TruthBody* t = frame.find(id);
      ASSERT_NE(b, nullptr);
      ASSERT_NE(t, nullptr);
      if (positions) {
        expect_within_half_a_quantum(b->x, t->x, q.position, "x", id);
        expect_within_half_a_quantum(b->y, t->y, q.position, "y", id);
      }
      expect_within_half_a_quantum(b->vx, t->vx, q.velocity, "vx", id);
      expect_within_half_a_quantum(b->vy, t->vy, q.velocity, "vy", id);
    }
  };
  check(snapshot.quantized().id_gaps(), true);
  check(snapshot.velocities().id_gaps(), false);
}

}  // namespace

FeedRun::FeedRun(scene::SceneDef scene, bool lockstep, std::uint64_t heartbeat,
                 std::shared_ptr<server::GameRules> rules)
    : sim_(std::move(scene), {}, std::move(rules)),
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

FakeClient& FeedRun::spectate(const wire::ViewSettings& settings) {
  const server::FeedClient id = next_id_++;
  feeds_.join(id, settings, std::nullopt);
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
    ASSERT_EQ(c.held.apply(snapshot, predictor_, c.settings.quantum), "");
    check_rounding(snapshot, c.held, frame_, c.settings.quantum);
    if (::testing::Test::HasFatalFailure()) return;
    // The hash on every snapshot without news and every k-th with it, so never more
    // than k snapshots apart.
    if (snapshot.has_view_hash()) {
      ASSERT_EQ(c.held.hash(), snapshot.view_hash())
          << "client " << c.id << " tick " << result.tick;
      c.since_hash = 0;
    } else {
      ++c.since_hash;
      ASSERT_LT(c.since_hash, c.settings.view_hash_interval)
          << "client " << c.id << " tick " << result.tick;
    }
    std::vector<std::uint64_t> ids;
    ASSERT_TRUE(wire::decode_id_gaps(snapshot.quantized().id_gaps(), ids));
    for (const auto id : ids) ++c.records_of[id];
    ASSERT_TRUE(wire::decode_id_gaps(snapshot.exact().id_gaps(), ids));
    for (const auto id : ids) ++c.records_of[id];
    ASSERT_TRUE(wire::decode_id_gaps(snapshot.velocities().id_gaps(), ids));
    for (const auto id : ids) ++c.records_of[id];
    for (const auto& body : snapshot.bodies()) ++c.records_of[body.body_id()];
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
