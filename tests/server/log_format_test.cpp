// The server's JSON logs (--log-format json): each message is one line holding one
// JSON object, whatever bytes the message holds.
#include "server/log_format.h"

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <string>

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

}  // namespace
