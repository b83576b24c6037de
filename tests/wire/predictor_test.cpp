// The predictor and the reconstruction both ends run (docs/PROTOCOL.md, section 5):
// the worked example of the page, computed here and found there byte for byte, and
// every malformed snapshot refused before it changes anything.
#include "wire/predictor.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "protocol_page.h"
#include "wire/framing.h"
#include "wire/reconstruction.h"

namespace {

std::string hex_bits(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "0x%016llx",
                static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(value)));
  return buffer;
}

physics::wire::Snapshot exact_snapshot(std::uint64_t tick, std::uint64_t id, double x, double y,
                                       double vx, double vy) {
  physics::wire::Snapshot s;
  s.set_tick(tick);
  auto* e = s.mutable_exact();
  e->add_id_gaps(id);
  e->add_x(x);
  e->add_y(y);
  e->add_vx(vx);
  e->add_vy(vy);
  return s;
}

TEST(Predictor, TheWorkedExampleOfTheProtocolPage) {
  const std::string page = protocol_page::text();
  ASSERT_FALSE(page.empty());
  const wire::Predictor predictor(60.0, 0.0, -9.81);
  const wire::Quantum quantum{0.001, 0.001};
  EXPECT_NE(page.find(hex_bits(predictor.dt())), std::string::npos);
  EXPECT_NE(page.find(hex_bits((0.5 * predictor.dt()) * predictor.dt())), std::string::npos);

  wire::PredictedBody body{7, 1.5, 2.0, 3.0, 4.0, wire::PredictorMode::Ballistic};
  for (int tick = 11; tick <= 12; ++tick) {
    predictor.advance(body);
    EXPECT_NE(page.find(hex_bits(body.x)), std::string::npos) << "x after tick " << tick;
    EXPECT_NE(page.find(hex_bits(body.y)), std::string::npos) << "y after tick " << tick;
    EXPECT_NE(page.find(hex_bits(body.vy)), std::string::npos) << "vy after tick " << tick;
  }

  wire::Reconstruction held;
  ASSERT_EQ(held.apply(exact_snapshot(10, 7, 1.5, 2.0, 3.0, 4.0), predictor, quantum), "");
  physics::wire::ServerMessage message;
  physics::wire::Snapshot& s = *message.mutable_snapshot();
  s.set_tick(12);
  auto* q = s.mutable_quantized();
  q->add_id_gaps(7);
  q->add_dx(12);
  q->add_dy(-7);
  q->add_dvx(0);
  q->add_dvy(-164);
  wire::Reconstruction after = held;
  ASSERT_EQ(after.apply(s, predictor, quantum), "");
  const wire::PredictedBody& got = after.bodies().at(0);
  for (const double v : {got.x, got.y, got.vx, got.vy}) {
    EXPECT_NE(page.find(hex_bits(v)), std::string::npos) << v;
  }
  char hash[32];
  std::snprintf(hash, sizeof hash, "0x%016llx", static_cast<unsigned long long>(after.hash()));
  EXPECT_NE(page.find(hash), std::string::npos) << hash;
  s.set_view_hash(after.hash());
  const std::vector<std::string> examples = protocol_page::wire_examples(page);
  ASSERT_EQ(examples.size(), 4u);
  EXPECT_EQ(protocol_page::hex(wire::encode_frame(message)), examples[2]);
}

// The second worked example of section 5.7: mode entries, each list counting its
// own records from 0. Quantized records 0, 1, 2 (bodies 3, 7, 9): body 7 becomes
// Glide (entry (1 << 2) | 1), body 9 Hold (entry (1 << 2) | 2: gap 2 - 1); the
// velocity record 0 (body 12) becomes Hold (entry (0 << 2) | 2).
TEST(Predictor, TheModesExampleOfTheProtocolPage) {
  const std::string page = protocol_page::text();
  const wire::Predictor predictor(60.0, 0.0, -9.81);
  physics::wire::ServerMessage message;
  physics::wire::Snapshot& s = *message.mutable_snapshot();
  s.set_tick(20);
  s.set_full(true);
  auto* q = s.mutable_quantized();
  for (const std::uint64_t gap : {3, 4, 2}) q->add_id_gaps(gap);
  for (const std::int64_t v : {1000, -1500, 3000}) q->add_dx(v);
  for (const std::int64_t v : {2000, 500, 100}) q->add_dy(v);
  for (const std::int64_t v : {0, 250, 0}) q->add_dvx(v);
  for (const std::int64_t v : {0, 0, 0}) q->add_dvy(v);
  q->add_modes((1u << 2) | 1u);
  q->add_modes((1u << 2) | 2u);
  auto* v = s.mutable_velocities();
  v->add_id_gaps(12);
  v->add_dvx(-40);
  v->add_dvy(10);
  v->add_modes((0u << 2) | 2u);
  wire::Reconstruction held;
  ASSERT_EQ(held.apply(s, predictor, {}), "");
  ASSERT_EQ(held.bodies().size(), 4u);
  const wire::PredictorMode expected[] = {wire::PredictorMode::Ballistic,
                                          wire::PredictorMode::Glide, wire::PredictorMode::Hold,
                                          wire::PredictorMode::Hold};
  const std::uint64_t ids[] = {3, 7, 9, 12};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(held.bodies()[i].id, ids[i]);
    EXPECT_EQ(held.bodies()[i].mode, expected[i]) << "body " << ids[i];
  }
  EXPECT_EQ(held.find(12)->x, 0.0);  // a velocity record for a body not held: from zero
  EXPECT_EQ(held.find(12)->vx, -40.0 * 0.001);
  char hash[32];
  std::snprintf(hash, sizeof hash, "0x%016llx", static_cast<unsigned long long>(held.hash()));
  EXPECT_NE(page.find(hash), std::string::npos) << hash;
  s.set_view_hash(held.hash());
  const std::vector<std::string> examples = protocol_page::wire_examples(page);
  ASSERT_EQ(examples.size(), 4u);
  EXPECT_EQ(protocol_page::hex(wire::encode_frame(message)), examples[3]);
}

// ENCODING_FULL's bodies are held as sent, in mode Hold, and hashed as the records
// of the other encodings; they must ascend.
TEST(Reconstruction, TheFullEncodingsBodiesAreHeldInModeHold) {
  const wire::Predictor predictor(60.0, 0.0, -9.81);
  physics::wire::Snapshot s;
  s.set_tick(5);
  s.set_full(true);
  for (const std::uint64_t id : {2, 9}) {
    physics::wire::BodyState* b = s.add_bodies();
    b->set_body_id(id);
    b->set_x(1.0);
    b->set_vy(-2.0);
  }
  wire::Reconstruction held;
  ASSERT_EQ(held.apply(s, predictor, {}), "");
  ASSERT_EQ(held.bodies().size(), 2u);
  for (const wire::PredictedBody& b : held.bodies()) {
    EXPECT_EQ(b.mode, wire::PredictorMode::Hold);
    EXPECT_EQ(b.x, 1.0);
    EXPECT_EQ(b.vy, -2.0);
  }
  s.mutable_bodies(1)->set_body_id(2);
  wire::Reconstruction other;
  EXPECT_NE(other.apply(s, predictor, {}), "");
  EXPECT_TRUE(other.bodies().empty());
}

TEST(Predictor, ModesMoveTheBodyAsTheTableSays) {
  const wire::Predictor predictor(50.0, 1.0, -10.0);
  wire::PredictedBody glide{1, 0.0, 0.0, 2.0, -1.0, wire::PredictorMode::Glide};
  predictor.advance(glide);
  EXPECT_EQ(glide.x, 2.0 * 0.02);
  EXPECT_EQ(glide.y, -1.0 * 0.02);
  EXPECT_EQ(glide.vy, -1.0);
  wire::PredictedBody hold{1, 5.0, 6.0, 2.0, -1.0, wire::PredictorMode::Hold};
  predictor.advance(hold);
  EXPECT_EQ(hold.x, 5.0);
  EXPECT_EQ(hold.vx, 2.0);
  // Ballistic from rest for one tick: x = g * dt^2 / 2, v = g * dt (hand-computed:
  // dt = 0.02, dt^2 / 2 = 0.0002).
  wire::PredictedBody fall{1, 0.0, 0.0, 0.0, 0.0, wire::PredictorMode::Ballistic};
  predictor.advance(fall);
  EXPECT_NEAR(fall.y, -0.002, 1e-18);
  EXPECT_NEAR(fall.vy, -0.2, 1e-16);
  EXPECT_NEAR(fall.x, 0.0002, 1e-19);
}

TEST(Reconstruction, RecordsReplaceAddAndLeaveInIdOrder) {
  const wire::Predictor predictor(60.0, 0.0, 0.0);
  wire::Reconstruction held;
  physics::wire::Snapshot s = exact_snapshot(1, 4, 1.0, 2.0, 0.0, 0.0);
  s.mutable_exact()->add_id_gaps(3);  // body 7
  for (auto* list : {s.mutable_exact()->mutable_x(), s.mutable_exact()->mutable_y(),
                     s.mutable_exact()->mutable_vx(), s.mutable_exact()->mutable_vy()}) {
    list->Add(0.5);
  }
  s.mutable_exact()->add_modes((1u << 2) | 2u);  // record 1 (body 7): Hold
  ASSERT_EQ(held.apply(s, predictor, {}), "");
  ASSERT_EQ(held.bodies().size(), 2u);
  EXPECT_EQ(held.bodies()[1].mode, wire::PredictorMode::Hold);
  physics::wire::Snapshot next;
  next.set_tick(2);
  next.add_left_gaps(4);
  ASSERT_EQ(held.apply(next, predictor, {}), "");
  ASSERT_EQ(held.bodies().size(), 1u);
  EXPECT_EQ(held.bodies()[0].id, 7u);
  EXPECT_EQ(held.bodies()[0].x, 0.5);  // held: it did not move with its velocity
  EXPECT_EQ(held.tick(), 2u);
}

TEST(Reconstruction, MalformedSnapshotsAreRefusedAndChangeNothing) {
  const wire::Predictor predictor(60.0, 0.0, -9.81);
  wire::Reconstruction held;
  ASSERT_EQ(held.apply(exact_snapshot(5, 2, 1.0, 1.0, 1.0, 1.0), predictor, {}), "");
  const std::uint64_t before = held.hash();
  std::vector<physics::wire::Snapshot> bad;
  {
    physics::wire::Snapshot s;  // lists of different lengths
    s.set_tick(6);
    s.mutable_quantized()->add_id_gaps(2);
    s.mutable_quantized()->add_dx(1);
    bad.push_back(s);
  }
  {
    physics::wire::Snapshot s = exact_snapshot(6, 3, 0, 0, 0, 0);  // ids not ascending
    auto* e = s.mutable_exact();
    e->add_id_gaps(0);
    e->add_x(0);
    e->add_y(0);
    e->add_vx(0);
    e->add_vy(0);
    bad.push_back(s);
  }
  {
    physics::wire::Snapshot s = exact_snapshot(6, 3, 0, 0, 0, 0);
    s.mutable_exact()->add_modes(3);  // mode 3 does not exist
    bad.push_back(s);
  }
  {
    physics::wire::Snapshot s = exact_snapshot(6, 3, 0, 0, 0, 0);
    s.mutable_exact()->add_modes((1u << 2) | 1u);  // names record 1 of 1
    bad.push_back(s);
  }
  {
    physics::wire::Snapshot s = exact_snapshot(6, 3, std::nan(""), 0, 0, 0);
    bad.push_back(s);
  }
  bad.push_back(exact_snapshot(4, 3, 0, 0, 0, 0));                          // tick goes back
  bad.push_back(exact_snapshot(5 + wire::kMaxTickGap + 1, 3, 0, 0, 0, 0));  // a jump
  {
    physics::wire::Snapshot s = exact_snapshot(6, 3, 0, 0, 0, 0);
    s.mutable_exact()->set_id_gaps(0, UINT64_MAX);
    s.mutable_exact()->add_id_gaps(2);  // overflows 64 bits
    for (auto* list : {s.mutable_exact()->mutable_x(), s.mutable_exact()->mutable_y(),
                       s.mutable_exact()->mutable_vx(), s.mutable_exact()->mutable_vy()}) {
      list->Add(0.0);
    }
    bad.push_back(s);
  }
  for (std::size_t i = 0; i < bad.size(); ++i) {
    EXPECT_NE(held.apply(bad[i], predictor, {}), "") << "case " << i;
    EXPECT_EQ(held.hash(), before) << "case " << i;
    EXPECT_EQ(held.tick(), 5u) << "case " << i;
  }
}

}  // namespace

namespace {

TEST(Reconstruction, AVelocityRecordKeepsThePositionHeld) {
  const wire::Predictor predictor(60.0, 0.0, 0.0);
  wire::Reconstruction held;
  ASSERT_EQ(held.apply(exact_snapshot(1, 5, 1.0, 2.0, 3.0, 4.0), predictor, {}), "");
  physics::wire::Snapshot s;
  s.set_tick(1);
  auto* v = s.mutable_velocities();
  v->add_id_gaps(5);
  v->add_dvx(-3000);
  v->add_dvy(500);
  v->add_modes(1);  // record 0: Glide
  ASSERT_EQ(held.apply(s, predictor, {0.001, 0.001}), "");
  const wire::PredictedBody& b = held.bodies().at(0);
  EXPECT_EQ(b.x, 1.0);
  EXPECT_EQ(b.y, 2.0);
  EXPECT_EQ(b.vx, 3.0 + -3000.0 * 0.001);
  EXPECT_EQ(b.vy, 4.0 + 500.0 * 0.001);
  EXPECT_EQ(b.mode, wire::PredictorMode::Glide);
  physics::wire::Snapshot bad;
  bad.set_tick(2);
  bad.mutable_velocities()->add_id_gaps(5);
  bad.mutable_velocities()->add_dvx(1);  // no dvy
  EXPECT_NE(held.apply(bad, predictor, {}), "");
  EXPECT_EQ(held.tick(), 1u);
}

}  // namespace
