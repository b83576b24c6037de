// A recording with one input changed: the replay reports the tick of that input as
// the first that differs (every earlier tick equal), and names the body it moved.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <memory>
#include <string>

#include "replay_support.h"
#include "replayer.h"

namespace {

using Kind = physics::recording::Record::KindCase;

// The recording of three clients over 200 ticks, with the input of `client` at
// `tick` (which must be one that was recorded) changed by 0.5 m/s^2 on x.
std::string recording_with_changed_input(std::uint32_t client, std::uint64_t tick,
                                         std::uint64_t* changed_body) {
  rtest::TempFile file("run.rec");
  rtest::record_in_process(file.path(), 3, 200);
  recording::LoadedRecording loaded = rtest::load_or_fail(file.path());
  bool changed = false;
  for (auto& record : loaded.records) {
    if (record.has_join() && record.join().client() == client) *changed_body = record.join().body();
    if (record.has_input() && record.input().client() == client && record.input().tick() == tick) {
      record.mutable_input()->set_ax(record.input().ax() + 0.5);
      changed = true;
    }
  }
  EXPECT_TRUE(changed) << "no input of client " << client << " at tick " << tick;
  return recording::encode_recording(loaded.header, loaded.records);
}

replay::ReplayReport check_bytes(std::string bytes) {
  auto opened = replay::Replayer::from_bytes(std::move(bytes));
  if (auto* error = std::get_if<recording::RecordingError>(&opened)) {
    ADD_FAILURE() << error->to_string();
    return {};
  }
  return replay::check_recording(*std::get<std::unique_ptr<replay::Replayer>>(opened));
}

bool names_body(const replay::ReplayReport& report, std::uint64_t body) {
  for (const auto& difference : report.bodies) {
    if (difference.body == body && difference.kind == replay::BodyDifference::Kind::Differs)
      return true;
  }
  return false;
}

TEST(ChangedInput, TheUnchangedRecordingReplaysEqual) {
  rtest::TempFile file("run.rec");
  const std::vector<std::uint64_t> hashes = rtest::record_in_process(file.path(), 3, 200);
  const replay::ReplayReport report = check_bytes(file.bytes());
  EXPECT_EQ(report.outcome, replay::ReplayReport::Outcome::Equal);
  EXPECT_EQ(report.ticks, 200u);
  EXPECT_EQ(report.hashes_checked, 200u);
  ASSERT_EQ(hashes.size(), 200u);
}

TEST(ChangedInput, ReportsTheTickOfTheChangedInputAndNoEarlierOne) {
  // Inputs change every 5 ticks: tick 95 holds one of client 2's.
  std::uint64_t body = 0;
  const replay::ReplayReport report = check_bytes(recording_with_changed_input(2, 95, &body));
  ASSERT_EQ(report.outcome, replay::ReplayReport::Outcome::Diverged);
  EXPECT_EQ(report.first_difference.tick, 95u);
  EXPECT_EQ(report.hashes_checked, 94u);  // ticks 1..94 all equal
  EXPECT_NE(report.first_difference.recorded_hash, report.first_difference.replayed_hash);
  // Body hashes come every 60 ticks: the first at or after 95 is tick 120.
  ASSERT_TRUE(report.bodies_tick.has_value());
  EXPECT_EQ(*report.bodies_tick, 120u);
  EXPECT_TRUE(names_body(report, body));
}

TEST(ChangedInput, AtATickWithBodyHashesNamesExactlyTheBodyMoved) {
  std::uint64_t body = 0;
  const replay::ReplayReport report = check_bytes(recording_with_changed_input(3, 120, &body));
  ASSERT_EQ(report.outcome, replay::ReplayReport::Outcome::Diverged);
  EXPECT_EQ(report.first_difference.tick, 120u);
  EXPECT_EQ(report.hashes_checked, 119u);
  ASSERT_TRUE(report.bodies_tick.has_value());
  EXPECT_EQ(*report.bodies_tick, 120u);
  // One step after the change only that body has moved differently.
  ASSERT_EQ(report.bodies.size(), 1u);
  EXPECT_EQ(report.bodies.front().body, body);
  ASSERT_TRUE(report.bodies.front().replayed.has_value());
}

std::string run_sim(const std::string& arguments, int* exit_code) {
  const std::string command = std::string(PHYSICS_SIM_EXE) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  std::array<char, 4096> chunk{};
  while (pipe && fgets(chunk.data(), static_cast<int>(chunk.size()), pipe)) out += chunk.data();
  const int status = pipe ? pclose(pipe) : -1;
  *exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

TEST(ChangedInput, PhysicsSimPrintsTheTickAndBodyAndExitsOne) {
  std::uint64_t body = 0;
  const std::string bytes = recording_with_changed_input(1, 60, &body);
  rtest::TempFile file("changed.rec");
  {
    std::FILE* out = std::fopen(file.path().c_str(), "wb");
    ASSERT_NE(out, nullptr);
    std::fwrite(bytes.data(), 1, bytes.size(), out);
    std::fclose(out);
  }
  int code = -1;
  const std::string out = run_sim("--replay " + file.path().string(), &code);
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("DIVERGED at tick 60"), std::string::npos) << out;
  EXPECT_NE(out.find("body " + std::to_string(body) + " "), std::string::npos) << out;

  rtest::TempFile equal("equal.rec");
  rtest::record_in_process(equal.path(), 2, 30);
  const std::string ok = run_sim("--replay " + equal.path().string(), &code);
  EXPECT_EQ(code, 0) << ok;
  EXPECT_NE(ok.find("replayed 30 ticks"), std::string::npos) << ok;

  const std::string bad = run_sim("--replay " + file.path().string() + ".missing", &code);
  EXPECT_EQ(code, 2) << bad;
  EXPECT_NE(bad.find("offset 0: cannot open"), std::string::npos) << bad;
}

}  // namespace
