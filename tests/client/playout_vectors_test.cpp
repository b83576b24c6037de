// The playout buffer against tests/vectors/playout_buffer.json, the cases the
// TypeScript client's PlayoutBuffer runs too
// (client/web/client/test/playout_vectors.test.mjs): a default or constant changed in
// one language fails that language's test.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "client/playout_buffer.h"
#include "vectors.h"

namespace {

using client::PlayoutBuffer;
using client::PlayoutFrame;
using client::PlayoutSettings;
using client::PushResult;
using nlohmann::json;

constexpr double kTolerance = 1e-9;

// The settings' fields by the vectors' names; false for a name it does not have.
bool set_field(PlayoutSettings& s, const std::string& name, double value) {
  if (name == "capacity") {
    s.capacity = static_cast<std::size_t>(value);
    return true;
  }
  double* fields[] = {&s.tick_rate, &s.send_interval, &s.send_intervals,    &s.jitter_multiplier,
                      &s.min_delay, &s.max_delay,     &s.max_extrapolation, &s.slew,
                      &s.snap,      &s.max_gap};
  const char* names[] = {"tick_rate", "send_interval", "send_intervals",    "jitter_multiplier",
                         "min_delay", "max_delay",     "max_extrapolation", "slew",
                         "snap",      "max_gap"};
  for (std::size_t i = 0; i < std::size(names); ++i) {
    if (name == names[i]) {
      *fields[i] = value;
      return true;
    }
  }
  return false;
}

PlayoutSettings settings_of(const json& overrides) {
  PlayoutSettings settings;
  for (const auto& [name, value] : overrides.items()) {
    EXPECT_TRUE(set_field(settings, name, vectors::number(value))) << "no setting " << name;
  }
  return settings;
}

const char* name_of(PushResult result) {
  switch (result) {
    case PushResult::Accepted:
      return "accepted";
    case PushResult::Reset:
      return "reset";
    case PushResult::Stale:
      return "stale";
    case PushResult::BadTime:
      return "bad-time";
    case PushResult::BadState:
      return "bad-state";
  }
  return "unknown";
}

client::Snapshot snapshot_of(std::uint64_t tick, const json& bodies) {
  client::Snapshot snapshot;
  snapshot.tick = tick;
  for (const json& b : bodies) {
    snapshot.bodies.push_back({b[0].get<std::uint64_t>(),
                               {vectors::number(b[1]), vectors::number(b[2])},
                               {vectors::number(b[3]), vectors::number(b[4])}});
  }
  return snapshot;
}

void check_frame(const PlayoutFrame& frame, const json& step, const std::string& where) {
  EXPECT_STREQ(client::to_string(frame.status), step["status"].get<std::string>().c_str()) << where;
  if (step.contains("server_time")) {
    EXPECT_NEAR(frame.server_time, step["server_time"].get<double>(), kTolerance) << where;
  }
  if (step.contains("lag")) {
    EXPECT_NEAR(frame.lag, step["lag"].get<double>(), kTolerance) << where;
  }
  if (step.contains("extrapolated")) {
    EXPECT_NEAR(frame.extrapolated, step["extrapolated"].get<double>(), kTolerance) << where;
  }
  if (step.contains("newest_tick")) {
    EXPECT_EQ(frame.newest_tick, step["newest_tick"].get<std::uint64_t>()) << where;
  }
  if (!step.contains("bodies")) return;
  ASSERT_EQ(frame.bodies.size(), step["bodies"].size()) << where;
  for (std::size_t i = 0; i < frame.bodies.size(); ++i) {
    const json& want = step["bodies"][i];
    const auto& body = frame.bodies[i];
    const auto id = want[0].get<std::uint64_t>();
    EXPECT_EQ(body.body_id, id) << where;
    EXPECT_NEAR(body.position.x, want[1].get<double>(), kTolerance) << where << ": body " << id;
    EXPECT_NEAR(body.position.y, want[2].get<double>(), kTolerance) << where << ": body " << id;
    EXPECT_NEAR(body.velocity.x, want[3].get<double>(), kTolerance) << where << ": body " << id;
    EXPECT_NEAR(body.velocity.y, want[4].get<double>(), kTolerance) << where << ": body " << id;
    if (step.contains("still")) {
      const auto& still = step["still"];
      EXPECT_EQ(body.still, std::find(still.begin(), still.end(), id) != still.end())
          << where << ": body " << id;
    }
  }
}

std::uint64_t stat(const client::PlayoutStats& stats, const std::string& name) {
  if (name == "accepted") return stats.accepted;
  if (name == "stale") return stats.stale;
  if (name == "bad_time") return stats.bad_time;
  if (name == "bad_state") return stats.bad_state;
  if (name == "resets") return stats.resets;
  if (name == "clock_backwards") return stats.clock_backwards;
  if (name == "snaps") return stats.snaps;
  if (name == "dropped") return stats.dropped;
  ADD_FAILURE() << "no stat " << name;
  return 0;
}

void run_step(PlayoutBuffer& buffer, const json& step, const std::string& where) {
  const std::string what = step.value("do", std::string());
  if (what == "push") {
    const PushResult result =
        buffer.push(snapshot_of(step["tick"].get<std::uint64_t>(), step["bodies"]),
                    vectors::number(step["arrival"]));
    EXPECT_STREQ(name_of(result), step["result"].get<std::string>().c_str()) << where;
    return;
  }
  if (what == "push_ticks") {
    const double rate = buffer.settings().tick_rate;
    for (auto tick = step["from"].get<std::uint64_t>(); tick <= step["to"].get<std::uint64_t>();
         ++tick) {
      buffer.push(snapshot_of(tick, step["bodies"]),
                  static_cast<double>(tick) / rate + step["transit"].get<double>());
    }
    return;
  }
  const std::string expect = step.value("expect", std::string());
  if (expect == "at_server_time") {
    check_frame(buffer.state_at_server_time(step["time"].get<double>()), step, where);
  } else if (expect == "state_at") {
    check_frame(buffer.state_at(step["now"].get<double>()), step, where);
  } else if (expect == "size") {
    EXPECT_EQ(buffer.size(), step["value"].get<std::size_t>()) << where;
  } else if (expect == "delay") {
    EXPECT_NEAR(buffer.delay(), step["value"].get<double>(), kTolerance) << where;
  } else if (expect == "jitter") {
    EXPECT_NEAR(buffer.jitter(), step["value"].get<double>(), kTolerance) << where;
  } else if (expect == "offset") {
    EXPECT_NEAR(buffer.offset(), step["value"].get<double>(), kTolerance) << where;
  } else if (expect == "stats") {
    for (const auto& [name, value] : step.items()) {
      if (name == "expect") continue;
      EXPECT_EQ(stat(buffer.stats(), name), value.get<std::uint64_t>()) << where << ": " << name;
    }
  } else {
    ADD_FAILURE() << where << ": no such step";
  }
}

TEST(PlayoutVectors, TheDefaultSettingsAreTheVectors) {
  const json vectors = vectors::load("playout_buffer");
  PlayoutSettings from_file;
  for (const auto& [name, value] : vectors["defaults"].items()) {
    ASSERT_TRUE(set_field(from_file, name, value.get<double>())) << "no setting " << name;
  }
  const PlayoutSettings defaults;
  EXPECT_EQ(defaults.tick_rate, from_file.tick_rate);
  EXPECT_EQ(defaults.send_interval, from_file.send_interval);
  EXPECT_EQ(defaults.send_intervals, from_file.send_intervals);
  EXPECT_EQ(defaults.jitter_multiplier, from_file.jitter_multiplier);
  EXPECT_EQ(defaults.min_delay, from_file.min_delay);
  EXPECT_EQ(defaults.max_delay, from_file.max_delay);
  EXPECT_EQ(defaults.max_extrapolation, from_file.max_extrapolation);
  EXPECT_EQ(defaults.slew, from_file.slew);
  EXPECT_EQ(defaults.snap, from_file.snap);
  EXPECT_EQ(defaults.max_gap, from_file.max_gap);
  EXPECT_EQ(defaults.capacity, from_file.capacity);
  EXPECT_EQ(vectors["defaults"].size(), 11u) << "every setting has its default in the file";
}

TEST(PlayoutVectors, SettingsInRangeAreAcceptedOutOfRangeRefusedWithTheirName) {
  const json vectors = vectors::load("playout_buffer");
  for (const json& range : vectors["ranges"]) {
    const std::string field = range["field"].get<std::string>();
    for (const json& value : range["valid"]) {
      PlayoutSettings settings;
      ASSERT_TRUE(set_field(settings, field, vectors::number(value))) << field;
      EXPECT_EQ(settings.validate(), "") << field << " = " << value;
    }
    for (const json& value : range["invalid"]) {
      PlayoutSettings settings;
      ASSERT_TRUE(set_field(settings, field, vectors::number(value))) << field;
      EXPECT_EQ(settings.validate().rfind(field + " = ", 0), 0u)
          << field << " = " << value << ": " << settings.validate();
    }
  }
}

TEST(PlayoutVectors, EveryCaseRunsAsTheVectorsSay) {
  const json vectors = vectors::load("playout_buffer");
  ASSERT_FALSE(vectors["cases"].empty());
  for (const json& vector : vectors["cases"]) {
    SCOPED_TRACE(vector["name"].get<std::string>());
    PlayoutBuffer buffer(settings_of(vector.value("settings", json::object())));
    std::size_t index = 0;
    for (const json& step : vector["steps"]) run_step(buffer, step, vectors::where(index++, step));
  }
}

}  // namespace
