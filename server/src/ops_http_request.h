#pragma once
// The smallest HTTP/1.1 request reader the operations endpoints need: a request line
// and headers, fed as they arrive, and never more than a fixed number of bytes held.
// Only GET and HEAD are served (a probe and a scrape have no body), so the headers
// are checked for their size and shape and otherwise ignored. Socket-free.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace server {

class OpsHttpRequest {
 public:
  enum class State : std::uint8_t {
    Incomplete,      // the blank line ending the headers has not arrived yet
    Complete,        // method() and target() are set
    HeaderTooLarge,  // over max_header_bytes before the blank line: answer 431
    Malformed,       // not a request line, or bytes no header holds: answer 400
  };

  explicit OpsHttpRequest(std::size_t max_header_bytes) : max_header_bytes_(max_header_bytes) {}

  // Appends bytes; at most max_header_bytes are ever kept, whatever is fed.
  State feed(std::string_view bytes);
  State state() const { return state_; }
  const std::string& method() const { return method_; }
  // The path with its query string cut off.
  const std::string& target() const { return target_; }
  std::size_t held_bytes() const { return held_.size(); }

 private:
  State parse_request_line(std::string_view line);

  std::size_t max_header_bytes_;
  std::string held_;
  State state_ = State::Incomplete;
  std::string method_;
  std::string target_;
};

}  // namespace server
