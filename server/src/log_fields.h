#pragma once
// A log line's fields beside its prose: the client (or connection) id, the peer's
// address, the tick, the reason and a byte count, each when the line has one. Text
// logs keep the prose alone (it names them already); --log-format json writes them
// as members of the line's object, after "message" (server/src/log_format.cpp).
#include <spdlog/spdlog.h>

#include <cstdint>
#include <optional>
#include <string_view>
#include <utility>

namespace server {

// Each member has an initializer, so that a line names only the fields it has
// ({.client = id, .tick = t}).
struct LogFields {
  std::optional<std::uint64_t> client{};  // "client_id": a client's or connection's id
  std::string_view address{};             // "address": the peer, ADDRESS:PORT; empty: none
  std::optional<std::uint64_t> tick{};    // "tick"
  std::string_view reason{};              // "reason"; empty: none
  std::optional<std::uint64_t> bytes{};   // "bytes"
};

namespace detail {
// The fields of the line being written on this thread (the loggers write in the
// caller's thread, so the formatter reads them while the line is formatted).
const LogFields* current_log_fields();
class LogFieldsScope {
 public:
  explicit LogFieldsScope(const LogFields& fields);
  ~LogFieldsScope();
  LogFieldsScope(const LogFieldsScope&) = delete;
  LogFieldsScope& operator=(const LogFieldsScope&) = delete;

 private:
  const LogFields* previous_;
};
}  // namespace detail

// spdlog::info(...) and the like, with the line's fields.
template <typename... Args>
void log_with(spdlog::level::level_enum level, const LogFields& fields,
              spdlog::format_string_t<Args...> format, Args&&... args) {
  if (!spdlog::should_log(level)) return;
  const detail::LogFieldsScope scope(fields);
  spdlog::log(level, format, std::forward<Args>(args)...);
}

}  // namespace server
