// The server's JSON logs (--log-format json): each message is one line holding one
// JSON object, whatever bytes the message holds.
#include "server/log_format.h"

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <string>

#include "log_fields.h"
#include "scene/scene.h"
#include "server/server.h"

namespace {

// The lines the default logger writes to stderr while `log` runs, in `format`; the
// default logger is put back afterwards.
template <typename Log>
std::string stderr_of(server::LogFormat format, Log log) {
  const std::shared_ptr<spdlog::logger> previous = spdlog::default_logger();
  ::testing::internal::CaptureStderr();
  server::use_stderr_log("log-format-test", format);
  log();
  spdlog::default_logger()->flush();
  const std::string written = ::testing::internal::GetCapturedStderr();
  spdlog::drop("log-format-test");
  spdlog::set_default_logger(previous);
  return written;
}

TEST(LogFormat, JsonLineHoldsTheMessageEscaped) {
  const std::string line = stderr_of(server::LogFormat::Json, [] {
    spdlog::warn("peer \"{}\" sent\n{}", "a\\b", std::string("\x01\xff", 2));
  });
  ASSERT_FALSE(line.empty());
  EXPECT_EQ(line.find('\n'), line.size() - 1) << "one line: " << line;
  EXPECT_EQ(line.rfind("{\"time\":\"", 0), 0u) << line;
  EXPECT_NE(line.find("\"level\":\"warning\",\"logger\":\"log-format-test\","), std::string::npos)
      << line;
  EXPECT_NE(line.find("\"message\":\"peer \\\"a\\\\b\\\" sent\\n\\u0001\\ufffd\"}\n"),
            std::string::npos)
      << line;
}

TEST(LogFormat, TextLineIsTheMessageAsItIs) {
  const std::string text =
      stderr_of(server::LogFormat::Text, [] { spdlog::info("plain \"quoted\" text"); });
  EXPECT_NE(text.find("plain \"quoted\" text"), std::string::npos) << text;
  EXPECT_EQ(text.find("\"message\""), std::string::npos) << text;
}

// A line's fields follow its message as members of the object, each only when the
// line has it; text keeps the prose alone.
TEST(LogFormat, JsonLineCarriesTheLinesFields) {
  const std::string line = stderr_of(server::LogFormat::Json, [] {
    server::log_with(spdlog::level::info,
                     {.client = 7,
                      .address = "10.0.0.2:4100",
                      .tick = 1200,
                      .reason = "said \"bye\"",
                      .bytes = 4096},
                     "client {} left", 7);
  });
  EXPECT_NE(line.find("\"message\":\"client 7 left\",\"client_id\":7,\"address\":\"10.0.0.2:"
                      "4100\",\"tick\":1200,\"reason\":\"said \\\"bye\\\"\",\"bytes\":4096}\n"),
            std::string::npos)
      << line;
  const std::string some = stderr_of(server::LogFormat::Json, [] {
    server::log_with(spdlog::level::warn, {.tick = 5}, "tick {} overran", 5);
  });
  EXPECT_NE(some.find("\"message\":\"tick 5 overran\",\"tick\":5}\n"), std::string::npos) << some;
  // A line logged without fields, after one with them, has none.
  const std::string none = stderr_of(server::LogFormat::Json, [] { spdlog::info("no fields"); });
  EXPECT_NE(none.find("\"message\":\"no fields\"}\n"), std::string::npos) << none;
  const std::string text = stderr_of(server::LogFormat::Text, [] {
    server::log_with(spdlog::level::info, {.client = 7}, "client {} left", 7);
  });
  EXPECT_NE(text.find("client 7 left"), std::string::npos) << text;
  EXPECT_EQ(text.find("client_id"), std::string::npos) << text;
}

// server::set_log_level: what a program embedding the server (a user's test) calls
// to keep the server's info lines (every join and leave) out of its output.
TEST(LogLevel, SetLogLevelHoldsBackLessSevereLines) {
  const spdlog::level::level_enum before = spdlog::get_level();
  server::set_log_level(server::LogLevel::Error);
  EXPECT_EQ(spdlog::get_level(), spdlog::level::err);
  const std::string written = stderr_of(server::LogFormat::Text, [] {
    spdlog::warn("a warning under level error");
    spdlog::error("an error under level error");
  });
  EXPECT_EQ(written.find("a warning"), std::string::npos) << written;
  EXPECT_NE(written.find("an error"), std::string::npos) << written;
  server::set_log_level(server::LogLevel::Off);
  EXPECT_EQ(spdlog::get_level(), spdlog::level::off);
  spdlog::set_level(before);
}

// ServerConfig::log_level is applied when the server is made; unset, the level stays.
TEST(LogLevel, TheServerConfigsLevelIsAppliedAndUnsetLeavesItAlone) {
  const spdlog::level::level_enum before = spdlog::get_level();
  server::ServerConfig config;
  config.port = 0;
  config.log_level = server::LogLevel::Error;
  {
    const server::Server quiet(config, scene::default_scene());
    EXPECT_EQ(spdlog::get_level(), spdlog::level::err);
  }
  config.log_level.reset();
  spdlog::set_level(spdlog::level::debug);
  {
    const server::Server untouched(config, scene::default_scene());
    EXPECT_EQ(spdlog::get_level(), spdlog::level::debug);
  }
  spdlog::set_level(before);
}

}  // namespace
