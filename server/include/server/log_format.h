#pragma once
// The server's log lines on stderr, as text for a person or as one JSON object a
// line for a log collector: {"time","level","logger","message"} and the line's fields
// (client_id, address, tick, reason, bytes: server/src/log_fields.h), time in UTC with
// microseconds. docs/SERVER.md, "Logs".
#include <string>

namespace server {

enum class LogFormat { Text, Json };
// The severities of spdlog, least severe first; Off writes nothing.
enum class LogLevel { Trace, Debug, Info, Warn, Error, Critical, Off };

// Sets the level of the default logger (the server's log lines).
void set_log_level(LogLevel level);

// Makes the default spdlog logger write to stderr in `format` under `name`.
void use_stderr_log(const std::string& name, LogFormat format);

}  // namespace server
