// Truncated, corrupted and wrong-version files, empty and huge fields: each gets an
// error that names the byte offset at fault, and none crashes or allocates from a
// length it has not checked.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <variant>

#include "replay_support.h"
#include "replayer.h"
#include "scene/scene.h"
#include "wire/framing.h"

namespace {

using replay::ReplayReport;

// A small valid recording: two clients, 30 ticks.
std::string small_recording() {
  rtest::TempFile file("small.rec");
  rtest::record_in_process(file.path(), 2, 30);
  return file.bytes();
}

// Opens and checks the bytes; BadFile carries the error.
ReplayReport check(std::string bytes) {
  auto opened = replay::Replayer::from_bytes(std::move(bytes));
  if (auto* error = std::get_if<recording::RecordingError>(&opened)) {
    ReplayReport report;
    report.outcome = ReplayReport::Outcome::BadFile;
    report.error = *error;
    return report;
  }
  return replay::check_recording(*std::get<std::unique_ptr<replay::Replayer>>(opened));
}

void expect_error(const std::string& bytes, std::uint64_t offset, const std::string& words) {
  const ReplayReport report = check(bytes);
  ASSERT_EQ(report.outcome, ReplayReport::Outcome::BadFile);
  EXPECT_EQ(report.error.offset, offset) << report.error.to_string();
  EXPECT_NE(report.error.message.find(words), std::string::npos) << report.error.to_string();
  EXPECT_EQ(report.error.to_string().rfind("offset " + std::to_string(offset) + ": ", 0), 0u);
}

std::string with_varint(std::string bytes, std::uint64_t value) {
  wire::append_varint_prefix(value, bytes);
  return bytes;
}

physics::recording::Header header_of(const std::string& bytes) {
  auto loaded = recording::load_recording_bytes(bytes);
  return std::get<recording::LoadedRecording>(loaded).header;
}

TEST(BadRecording, EveryTruncationIsAnErrorAtTheCutRecordOrAShorterValidFile) {
  const std::string bytes = small_recording();
  auto loaded = recording::load_recording_bytes(bytes);
  ASSERT_TRUE(std::holds_alternative<recording::LoadedRecording>(loaded));
  const auto& full = std::get<recording::LoadedRecording>(loaded);
  const std::uint64_t header_prefix = recording::kPreambleBytes;
  for (std::size_t cut = 0; cut < bytes.size(); ++cut) {
    const ReplayReport report = check(bytes.substr(0, cut));
    // A cut exactly between two records leaves a shorter recording that is valid.
    bool at_boundary = false;
    for (const std::uint64_t offset : full.offsets) at_boundary |= offset == cut;
    if (at_boundary) {
      EXPECT_EQ(report.outcome, ReplayReport::Outcome::Equal) << "cut " << cut;
      continue;
    }
    ASSERT_EQ(report.outcome, ReplayReport::Outcome::BadFile) << "cut " << cut;
    EXPECT_NE(report.error.message.find("truncated"), std::string::npos)
        << "cut " << cut << ": " << report.error.to_string();
    // The offset named is where the cut message starts.
    std::uint64_t expected = cut < header_prefix ? cut : header_prefix;
    for (const std::uint64_t offset : full.offsets) {
      if (offset < cut) expected = offset;
    }
    EXPECT_EQ(report.error.offset, expected) << "cut " << cut << ": " << report.error.to_string();
  }
}

TEST(BadRecording, WrongMagicIsRefusedAtOffsetZero) {
  std::string bytes = small_recording();
  bytes[0] = 'X';
  expect_error(bytes, 0, "not a recording");
  expect_error("", 0, "truncated");
}

TEST(BadRecording, WrongVersionIsRefusedAtOffsetEight) {
  std::string bytes = small_recording();
  bytes[8] = 2;
  expect_error(bytes, 8, "unsupported version 2");
  bytes[8] = 1;
  bytes[11] = 1;  // version 2^24 + 1
  expect_error(bytes, 8, "unsupported version 16777217");
}

TEST(BadRecording, CorruptedRecordBytesAreRefusedAtThatRecord) {
  const std::string bytes = small_recording();
  auto loaded = std::get<recording::LoadedRecording>(recording::load_recording_bytes(bytes));
  ASSERT_GT(loaded.offsets.size(), 10u);
  const std::uint64_t at = loaded.offsets[10];
  std::string corrupted = bytes;
  // Keep the length prefix (one byte for these small records), garble the message:
  // 0xFF bytes make a varint that never ends.
  const auto length = static_cast<std::size_t>(static_cast<unsigned char>(bytes[at]));
  ASSERT_LT(length, 0x80u);
  std::memset(corrupted.data() + at + 1, 0xFF, length);
  expect_error(corrupted, at, "does not parse");
}

TEST(BadRecording, ACorruptedHashIsADivergenceAtItsTick) {
  const std::string bytes = small_recording();
  auto loaded = std::get<recording::LoadedRecording>(recording::load_recording_bytes(bytes));
  for (auto& record : loaded.records) {
    if (record.has_tick_hash() && record.tick_hash().tick() == 17) {
      record.mutable_tick_hash()->set_state_hash(record.tick_hash().state_hash() ^ 1u);
    }
  }
  const ReplayReport report = check(recording::encode_recording(loaded.header, loaded.records));
  ASSERT_EQ(report.outcome, ReplayReport::Outcome::Diverged);
  EXPECT_EQ(report.first_difference.tick, 17u);
  EXPECT_EQ(report.hashes_checked, 16u);
}

TEST(BadRecording, HugeLengthPrefixesAreRefusedBeforeAnythingIsAllocated) {
  const std::string bytes = small_recording();
  const std::uint64_t end = bytes.size();
  // Over the record limit: refused on the prefix alone.
  expect_error(with_varint(bytes, std::uint64_t{1} << 40), end, "over the limit");
  expect_error(with_varint(bytes, std::numeric_limits<std::uint64_t>::max()), end,
               "over the limit");
  // Under the limit but past the end of the file.
  expect_error(with_varint(bytes, 1000) + "abcde", end, "only 5 left");
  // A varint longer than 64 bits.
  expect_error(bytes + std::string(11, '\xFF'), end, "bad length prefix");
  // The header's own limit.
  expect_error(with_varint(recording::encode_preamble(), recording::kMaxHeaderBytes + 1),
               recording::kPreambleBytes, "over the limit");
}

TEST(BadRecording, EmptyRecordsAndHeadersAreRefused) {
  const std::string bytes = small_recording();
  expect_error(bytes + std::string(1, '\0'), bytes.size(), "empty record");
  expect_error(recording::encode_preamble() + std::string(1, '\0'), recording::kPreambleBytes,
               "empty header");
  expect_error(recording::encode_preamble(), recording::kPreambleBytes, "no header");
}

TEST(BadRecording, AHugeFieldInsideARecordDoesNotParse) {
  const std::string bytes = small_recording();
  // A Record whose tick_hash (field 4, length-delimited: tag 0x22) claims 2^35 bytes.
  std::string record("\x22", 1);
  wire::append_varint_prefix(std::uint64_t{1} << 35, record);
  std::string file = bytes;
  wire::append_varint_prefix(record.size(), file);
  expect_error(file + record, bytes.size(), "does not parse");
}

TEST(BadRecording, HeadersWithoutAUsableRunAreRefusedAtTheHeader) {
  const std::string bytes = small_recording();
  const physics::recording::Header good = header_of(bytes);
  const auto encode = [](const physics::recording::Header& header) {
    return recording::encode_recording(header, {});
  };
  auto prefix_bytes = [](const physics::recording::Header& header) {
    std::string prefix;
    wire::append_varint_prefix(header.ByteSizeLong(), prefix);
    return prefix.size();
  };
  physics::recording::Header no_scene = good;
  no_scene.mutable_server()->clear_scene();
  expect_error(encode(no_scene), recording::kPreambleBytes + prefix_bytes(no_scene), "no scene");

  physics::recording::Header no_spawn = good;
  no_spawn.mutable_server()->mutable_scene()->clear_spawn_points();
  expect_error(encode(no_spawn), recording::kPreambleBytes + prefix_bytes(no_spawn),
               "spawn_points: empty");

  physics::recording::Header bad_rate = good;
  bad_rate.mutable_server()->set_tick_rate(std::numeric_limits<double>::quiet_NaN());
  expect_error(encode(bad_rate), recording::kPreambleBytes + prefix_bytes(bad_rate),
               "tick rate must be in");

  physics::recording::Header no_hashes = good;
  no_hashes.mutable_server()->set_hash_every(0);
  expect_error(encode(no_hashes), recording::kPreambleBytes + prefix_bytes(no_hashes),
               "hash_every 0");

  physics::recording::Header bad_body = good;
  bad_body.mutable_server()->mutable_scene()->mutable_bodies(0)->set_shape(
      physics::recording::SHAPE_UNSPECIFIED);
  expect_error(encode(bad_body), recording::kPreambleBytes + prefix_bytes(bad_body),
               "bodies[0]: unknown shape");

  physics::recording::Header bad_world = good;
  bad_world.mutable_server()->mutable_scene()->mutable_world()->set_substeps(0);
  expect_error(encode(bad_world), recording::kPreambleBytes + prefix_bytes(bad_world),
               "scene.world");

  physics::recording::Header client;
  client.mutable_client()->set_name("c");
  expect_error(encode(client), recording::kPreambleBytes + prefix_bytes(client),
               "client recording");
}

// Found by tests/fuzz/replay_fuzz (a longer run): bodies at x = -1e308 and +1e308 in
// a world without bounds made the broadphase's cell-growing loop endless, so
// physics-sim --replay hung at the first step. The recording's scene gets the scene
// loader's checks: such positions (beyond |coordinate| 1e7), spawn points there, and
// speeds over world.max_speed are refused at the header. The seed
// tests/fuzz/corpus/replay/bodies_at_plus_and_minus_1e308 is this recording.
TEST(BadRecording, BodiesBeyondTheCoordinateLimitAreRefusedAtTheHeader) {
  const std::string bytes = small_recording();
  physics::recording::Header header = header_of(bytes);
  physics::recording::Scene& scene = *header.mutable_server()->mutable_scene();
  scene.mutable_world()->set_has_bounds(false);
  ASSERT_GE(scene.bodies_size(), 2);
  scene.mutable_bodies(0)->mutable_position()->set_x(-1e308);
  scene.mutable_bodies(1)->mutable_position()->set_x(1e308);
  std::string prefix;
  wire::append_varint_prefix(header.ByteSizeLong(), prefix);
  const std::uint64_t at = recording::kPreambleBytes + prefix.size();
  expect_error(recording::encode_recording(header, {}), at,
               "scene.bodies[0]: position is not finite or beyond the largest |coordinate| 1e7");

  physics::recording::Header far_spawn = header_of(bytes);
  far_spawn.mutable_server()->mutable_scene()->mutable_spawn_points(0)->set_y(2e7);
  prefix.clear();
  wire::append_varint_prefix(far_spawn.ByteSizeLong(), prefix);
  expect_error(recording::encode_recording(far_spawn, {}),
               recording::kPreambleBytes + prefix.size(),
               "scene.spawn_points: not finite or beyond");

  physics::recording::Header fast = header_of(bytes);
  physics::recording::BodyDef& body = *fast.mutable_server()->mutable_scene()->mutable_bodies(
      fast.server().scene().bodies_size() - 1);
  body.set_is_static(false);
  body.mutable_velocity()->set_x(1e6);
  prefix.clear();
  wire::append_varint_prefix(fast.ByteSizeLong(), prefix);
  expect_error(recording::encode_recording(fast, {}), recording::kPreambleBytes + prefix.size(),
               "velocity is not finite or above world.max_speed");
}

// Found by tests/fuzz/replay_fuzz: a tick rate that is finite and above zero but
// so small (a denormal) that dt = 1 / rate is infinite reached World::step's assert.
// Such rates are refused at the header, by the range physics-server's --tick-rate
// has (scene/scene.h); so is a rate just above it, and 0 (which is no rate here).
TEST(BadRecording, ATickRateWhoseStepIsInfiniteIsRefusedAtTheHeader) {
  const std::string bytes = small_recording();
  for (const double rate :
       {9.62876890084745e-310, std::numeric_limits<double>::min(), 1e-4,
        std::nextafter(scene::kMinTickRate, 0.0), 0.0, std::nextafter(scene::kMaxTickRate, 1e9)}) {
    SCOPED_TRACE(rate);
    physics::recording::Header header = header_of(bytes);
    header.mutable_server()->set_tick_rate(rate);
    std::string prefix;
    wire::append_varint_prefix(header.ByteSizeLong(), prefix);
    expect_error(recording::encode_recording(header, {}), recording::kPreambleBytes + prefix.size(),
                 "tick rate must be in [0.001, 1000]");
  }
}

TEST(BadRecording, ATickRateAtEitherEndOfTheRangeOpens) {
  const std::string bytes = small_recording();
  for (const double rate : {scene::kMinTickRate, scene::kMaxTickRate}) {
    SCOPED_TRACE(rate);
    physics::recording::Header header = header_of(bytes);
    header.mutable_server()->set_tick_rate(rate);
    auto opened = replay::Replayer::from_bytes(recording::encode_recording(header, {}));
    ASSERT_TRUE(std::holds_alternative<std::unique_ptr<replay::Replayer>>(opened))
        << std::get<recording::RecordingError>(opened).to_string();
  }
}

TEST(BadRecording, RecordsThatMakeNoSenseAreRefusedAtTheirOffset) {
  const std::string bytes = small_recording();
  const auto append = [&](const physics::recording::Record& record, std::uint64_t* at) {
    *at = bytes.size();
    std::string out = bytes;
    wire::append_frame(record, out);
    return out;
  };
  std::uint64_t at = 0;
  physics::recording::Record jump;
  jump.mutable_tick_hash()->set_tick(std::uint64_t{1} << 60);
  std::string file = append(jump, &at);
  expect_error(file, at, "jumps");

  physics::recording::Record back;
  back.mutable_join()->set_tick(3);
  back.mutable_join()->set_client(9);
  file = append(back, &at);
  expect_error(file, at, "out of order");

  physics::recording::Record stranger;
  stranger.mutable_input()->set_tick(31);
  stranger.mutable_input()->set_client(77);
  file = append(stranger, &at);
  expect_error(file, at, "not in the room");

  physics::recording::Record nan;
  nan.mutable_input()->set_tick(31);
  nan.mutable_input()->set_client(1);
  nan.mutable_input()->set_ax(std::numeric_limits<double>::infinity());
  file = append(nan, &at);
  expect_error(file, at, "not finite");

  physics::recording::Record received;
  received.mutable_received()->set_micros(1);
  file = append(received, &at);
  expect_error(file, at, "Received");

  physics::recording::Record twice;
  twice.mutable_join()->set_tick(30);
  twice.mutable_join()->set_client(1);
  file = append(twice, &at);
  expect_error(file, at, "already in the room");
}

TEST(BadRecording, AMissingFileIsRefusedAtOffsetZero) {
  const ReplayReport report = replay::check_recording_file("/nonexistent/dir/run.rec");
  ASSERT_EQ(report.outcome, ReplayReport::Outcome::BadFile);
  EXPECT_EQ(report.error.offset, 0u);
  EXPECT_NE(report.error.message.find("cannot open"), std::string::npos);
}

}  // namespace
