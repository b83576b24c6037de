// The input clock against tests/vectors/input_clock.json, the cases the TypeScript
// client's InputClock runs too (client/web/client/test/input_clock_vectors.test.mjs):
// a constant changed in one language fails that language's test.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>

#include "client/input_clock.h"
#include "vectors.h"

namespace {

using client::InputClock;
using client::InputClockConfig;
using nlohmann::json;
using std::chrono::nanoseconds;

nanoseconds from_ms(double ms) { return nanoseconds(std::llround(ms * 1e6)); }
double to_ms(nanoseconds ns) { return static_cast<double>(ns.count()) / 1e6; }

InputClockConfig config_of(const json& config) {
  InputClockConfig c;
  if (config.contains("tick_rate")) c.tick_rate = config["tick_rate"].get<double>();
  if (config.contains("safety_ms"))
    c.safety = std::chrono::microseconds(std::llround(config["safety_ms"].get<double>() * 1000.0));
  if (config.contains("max_delay")) c.max_delay = config["max_delay"].get<std::uint32_t>();
  if (config.contains("fixed_delay")) c.fixed_delay = config["fixed_delay"].get<std::uint32_t>();
  return c;
}

// One case: the clock, and the server's path its times are written against.
class ClockRun {
 public:
  explicit ClockRun(const json& vector)
      : clock_(config_of(vector.value("config", json::object()))),
        origin_(from_ms(vector["path"]["origin_ms"].get<double>())),
        one_way_(from_ms(vector["path"]["one_way_ms"].get<double>())) {}

  // The server steps tick t at origin + t of the clock's own periods.
  InputClock::time_point at(const json& time) const {
    nanoseconds t = from_ms(time.value("plus_ms", 0.0));
    if (time.contains("ms")) {
      t += from_ms(time["ms"].get<double>());
    } else if (time.contains("stepped")) {
      t += origin_ + clock_.period() * time["stepped"].get<std::int64_t>();
    } else {
      t += origin_ + clock_.period() * time["seen"].get<std::int64_t>() + one_way_;
    }
    return InputClock::time_point{} + t;
  }
  InputClock::time_point seen(std::int64_t tick) const { return at(json{{"seen", tick}}); }

  void run(const json& step, const std::string& where) {
    const std::string what = step.value("do", std::string());
    if (what == "round_trip") {
      clock_.on_round_trip(from_ms(step["ms"].get<double>()), at(step["at"]));
    } else if (what == "round_trips") {
      for (int i = 0; i < step["count"].get<int>(); ++i)
        clock_.on_round_trip(from_ms(step["ms"].get<double>()), at(step["at"]));
    } else if (what == "tick_seen") {
      clock_.on_tick_seen(step["tick"].get<std::uint64_t>(), at(step["at"]));
    } else if (what == "ticks_seen") {
      for (auto t = step["from"].get<std::int64_t>(); t <= step["to"].get<std::int64_t>(); ++t)
        clock_.on_tick_seen(static_cast<std::uint64_t>(t), seen(t));
    } else if (what == "margin") {
      clock_.on_margin(std::chrono::microseconds(step["us"].get<std::int64_t>()), at(step["at"]));
    } else if (what == "margins") {
      for (auto t = step["from"].get<std::int64_t>(); t <= step["to"].get<std::int64_t>(); ++t)
        clock_.on_margin(std::chrono::microseconds(step["us"].get<std::int64_t>()), seen(t));
    } else if (what == "waiting_at") {
      clock_.on_waiting_at(step["tick"].get<std::uint64_t>());
    } else if (what == "server_falls_behind") {
      origin_ += from_ms(step["ms"].get<double>());
    } else {
      check(step, where);
    }
  }

 private:
  void check(const json& step, const std::string& where) {
    const std::string what = step.value("expect", std::string());
    if (what == "server_tick") {
      EXPECT_NEAR(clock_.server_tick(at(step["at"])), step["value"].get<double>(),
                  step["tolerance"].get<double>())
          << where;
    } else if (what == "send_up_to") {
      EXPECT_EQ(clock_.send_up_to(at(step["at"])), step["value"].get<std::uint64_t>()) << where;
    } else if (what == "next_send_time") {
      using namespace std::chrono_literals;
      const auto next = clock_.next_send_time(at(step["from"]));
      EXPECT_NEAR(to_ms(next - at(step["value"])), 0.0, step["tolerance"].get<double>()) << where;
      EXPECT_EQ(clock_.send_up_to(next - 1us), step["send_up_to_before"].get<std::uint64_t>())
          << where << ": just before";
      EXPECT_EQ(clock_.send_up_to(next + 1us), step["send_up_to_after"].get<std::uint64_t>())
          << where << ": just after";
    } else if (what == "lead_ms") {
      EXPECT_NEAR(to_ms(clock_.lead()), step["value"].get<double>(),
                  step["tolerance"].get<double>())
          << where;
    } else if (what == "round_trip_ms") {
      ASSERT_TRUE(clock_.round_trip().has_value()) << where;
      EXPECT_NEAR(to_ms(*clock_.round_trip()), step["value"].get<double>(),
                  step["tolerance"].get<double>())
          << where;
    } else if (what == "delay") {
      EXPECT_EQ(clock_.delay(), step["value"].get<std::uint32_t>()) << where;
    } else if (what == "raises") {
      EXPECT_EQ(clock_.raises(), step["value"].get<std::uint64_t>()) << where;
    } else if (what == "lowers") {
      EXPECT_EQ(clock_.lowers(), step["value"].get<std::uint64_t>()) << where;
    } else {
      ADD_FAILURE() << where << ": no such step";
    }
  }

  InputClock clock_;
  nanoseconds origin_;
  nanoseconds one_way_;
};

TEST(InputClockVectors, TheDefaultConfigIsTheVectors) {
  const json vectors = vectors::load("input_clock");
  const InputClockConfig defaults;
  EXPECT_EQ(defaults.safety, std::chrono::microseconds(std::llround(
                                 vectors["defaults"]["safety_ms"].get<double>() * 1000.0)));
  EXPECT_EQ(defaults.max_delay, vectors["defaults"]["max_delay"].get<std::uint32_t>());
}

TEST(InputClockVectors, EveryCaseRunsAsTheVectorsSay) {
  const json vectors = vectors::load("input_clock");
  ASSERT_FALSE(vectors["cases"].empty());
  for (const json& vector : vectors["cases"]) {
    SCOPED_TRACE(vector["name"].get<std::string>());
    ClockRun run(vector);
    std::size_t index = 0;
    for (const json& step : vector["steps"]) run.run(step, vectors::where(index++, step));
  }
}

}  // namespace
