#include "log_limiter.h"

#include <google/protobuf/stubs/logging.h>

#include <cstdio>
#include <mutex>

namespace server {

LogLimiter::LogLimiter(std::size_t lines_per_window, clock::duration window)
    : lines_per_window_(lines_per_window), window_(window) {}

bool LogLimiter::admit(const char* cause, clock::time_point now, const std::string& address) {
  Window& w = causes_[cause];
  if (now - w.started >= window_) {
    // The previous window's suppressed lines are reported by flush(); keep them.
    if (w.suppressed == 0) {
      w.started = now;
      w.admitted = 0;
    }
  }
  if (w.admitted < lines_per_window_ && now - w.started < window_) {
    ++w.admitted;
    return true;
  }
  ++w.suppressed;
  ++suppressed_total_;
  if (!address.empty() && w.addresses.size() < kMaxCountedAddresses) w.addresses.insert(address);
  return false;
}

void LogLimiter::flush(
    clock::time_point now,
    const std::function<void(const std::string&, std::uint64_t, std::size_t)>& report) {
  for (auto& [cause, w] : causes_) {
    if (now - w.started < window_ || w.suppressed == 0) continue;
    report(cause, w.suppressed, w.addresses.size());
    w = Window{now, 0, 0, {}};
  }
}

namespace {

void protobuf_log(google::protobuf::LogLevel level, const char* filename, int line,
                  const std::string& message) {
  if (level != google::protobuf::LOGLEVEL_FATAL) return;
  std::fprintf(stderr, "[libprotobuf FATAL %s:%d] %s\n", filename, line, message.c_str());
}

}  // namespace

void silence_protobuf_log() {
  static std::once_flag once;
  std::call_once(once, [] { google::protobuf::SetLogHandler(&protobuf_log); });
}

}  // namespace server
