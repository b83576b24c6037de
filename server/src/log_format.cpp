#include "server/log_format.h"

#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdint>
#include <iterator>
#include <memory>
#include <optional>
#include <string>

#include "log_fields.h"
#include "text/json_escape.h"

namespace server {

namespace detail {
namespace {
thread_local const LogFields* current_fields = nullptr;
}  // namespace
const LogFields* current_log_fields() { return current_fields; }
LogFieldsScope::LogFieldsScope(const LogFields& fields) : previous_(current_fields) {
  current_fields = &fields;
}
LogFieldsScope::~LogFieldsScope() { current_fields = previous_; }
}  // namespace detail

namespace {

// %* in the JSON pattern: the message, escaped to sit inside a JSON string.
class JsonMessageFlag final : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& msg, const std::tm&,
              spdlog::memory_buf_t& dest) override {
    const std::string escaped = text::json_escape({msg.payload.data(), msg.payload.size()});
    dest.append(escaped.data(), escaped.data() + escaped.size());
  }
  std::unique_ptr<custom_flag_formatter> clone() const override {
    return std::make_unique<JsonMessageFlag>();
  }
};

// %& in the JSON pattern: the line's fields (log_fields.h), each as `,"name":value`;
// nothing for a line logged without them.
class JsonFieldsFlag final : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg&, const std::tm&,
              spdlog::memory_buf_t& dest) override {
    const LogFields* fields = detail::current_log_fields();
    if (fields == nullptr) return;
    const auto number = [&](const char* name, const std::optional<std::uint64_t>& value) {
      if (value) fmt::format_to(std::back_inserter(dest), ",\"{}\":{}", name, *value);
    };
    const auto text = [&](const char* name, std::string_view value) {
      if (!value.empty())
        fmt::format_to(std::back_inserter(dest), ",\"{}\":\"{}\"", name, text::json_escape(value));
    };
    number("client_id", fields->client);
    text("address", fields->address);
    number("tick", fields->tick);
    text("reason", fields->reason);
    number("bytes", fields->bytes);
  }
  std::unique_ptr<custom_flag_formatter> clone() const override {
    return std::make_unique<JsonFieldsFlag>();
  }
};

}  // namespace

static_assert(static_cast<int>(LogLevel::Trace) == spdlog::level::trace &&
                  static_cast<int>(LogLevel::Error) == spdlog::level::err &&
                  static_cast<int>(LogLevel::Off) == spdlog::level::off,
              "LogLevel lists spdlog's levels in spdlog's order");

void set_log_level(LogLevel level) {
  spdlog::set_level(static_cast<spdlog::level::level_enum>(level));
}

void use_stderr_log(const std::string& name, LogFormat format) {
  spdlog::drop(name);
  if (format == LogFormat::Text) {
    spdlog::set_default_logger(spdlog::stderr_color_mt(name));
    return;
  }
  auto logger = spdlog::stderr_logger_mt(name);
  auto formatter = std::make_unique<spdlog::pattern_formatter>(spdlog::pattern_time_type::utc);
  formatter->add_flag<JsonMessageFlag>('*');
  formatter->add_flag<JsonFieldsFlag>('&').set_pattern(
      R"({"time":"%Y-%m-%dT%H:%M:%S.%fZ","level":"%l","logger":"%n","message":"%*"%&})");
  logger->set_formatter(std::move(formatter));
  spdlog::set_default_logger(std::move(logger));
}

}  // namespace server
