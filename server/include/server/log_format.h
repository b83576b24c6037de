#pragma once
// The server's log lines on stderr, as text for a person or as one JSON object a
// line for a log collector: {"time","level","logger","message"}, time in UTC with
// microseconds. docs/SERVER.md, "Logs".
#include <string>

namespace server {

enum class LogFormat { Text, Json };

// Makes the default spdlog logger write to stderr in `format` under `name`.
void use_stderr_log(const std::string& name, LogFormat format);

}  // namespace server
