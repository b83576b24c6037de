#pragma once
// Log lines a stranger can cause (one per connection, per refusal, per bad frame)
// are rate-limited per cause, so that a flood costs us a few lines a second and a
// count, not a synchronous write per connection. Clock-free: the caller passes
// the time.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>

namespace server {

class LogLimiter {
 public:
  using clock = std::chrono::steady_clock;

  // At most `lines_per_window` lines of each cause in each `window`.
  LogLimiter(std::size_t lines_per_window, clock::duration window);

  // True when a line of `cause` may be written now; false counts it as suppressed,
  // and `address` (if given) among the distinct addresses of the suppressed lines.
  bool admit(const char* cause, clock::time_point now, const std::string& address = {});
  // For each cause whose window has ended with lines suppressed in it: calls
  // report(cause, count, addresses) and starts it afresh; `addresses` counts the
  // distinct ones given (at most kMaxCountedAddresses). The server calls this
  // periodically, so a count is reported even when no later line of its cause comes:
  // one aggregate line per cause and window, however many addresses there are.
  void flush(clock::time_point now,
             const std::function<void(const std::string&, std::uint64_t, std::size_t)>& report);

  // Distinct addresses remembered per cause and window; past it they are not told apart.
  static constexpr std::size_t kMaxCountedAddresses = 4096;

  std::uint64_t suppressed_total() const { return suppressed_total_; }

 private:
  struct Window {
    clock::time_point started{};
    std::size_t admitted = 0;
    std::uint64_t suppressed = 0;
    std::set<std::string> addresses;  // of the suppressed lines
  };
  std::size_t lines_per_window_;
  clock::duration window_;
  std::map<std::string, Window> causes_;  // a handful of fixed causes
  std::uint64_t suppressed_total_ = 0;
};

// Routes libprotobuf's own log (a line for every frame with a bad UTF-8 string, say)
// away from stderr: a peer's bad bytes are already answered with an Error. Fatal
// messages still reach stderr. Process-wide and idempotent.
void silence_protobuf_log();

}  // namespace server
