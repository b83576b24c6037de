#include "ops_http_request.h"

#include <algorithm>

namespace server {
namespace {

// Bytes a request line or header may hold: visible ASCII, space, tab, and the CR of
// the line ends. Anything else (NUL, other controls) is refused as a request.
bool allowed_byte(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u == '\t' || u == '\r' || u == '\n' || (u >= 0x20 && u != 0x7f);
}

}  // namespace

OpsHttpRequest::State OpsHttpRequest::feed(std::string_view bytes) {
  if (state_ != State::Incomplete) return state_;
  // Only what fits under the cap is kept; one byte over is enough to know.
  const std::size_t room = max_header_bytes_ - std::min(max_header_bytes_, held_.size());
  const std::size_t taken = std::min(room, bytes.size());
  const std::size_t searched_from = held_.size() >= 3 ? held_.size() - 3 : 0;
  held_.append(bytes.substr(0, taken));
  if (!std::all_of(held_.begin() + static_cast<std::ptrdiff_t>(searched_from), held_.end(),
                   allowed_byte)) {
    return state_ = State::Malformed;
  }
  // The headers end at a blank line (CRLF CRLF, or LF LF from lenient senders).
  const bool ended = held_.find("\r\n\r\n", searched_from) != std::string::npos ||
                     held_.find("\n\n", searched_from) != std::string::npos;
  if (!ended) {
    return state_ = held_.size() >= max_header_bytes_ ? State::HeaderTooLarge : State::Incomplete;
  }
  const std::size_t line_end = held_.find('\n');
  std::string_view line(held_.data(), line_end);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return state_ = parse_request_line(line);
}

// "METHOD SP TARGET SP HTTP/1.x"
OpsHttpRequest::State OpsHttpRequest::parse_request_line(std::string_view line) {
  const std::size_t first = line.find(' ');
  const std::size_t last = line.rfind(' ');
  if (first == std::string_view::npos || first == last || first == 0) return State::Malformed;
  const std::string_view version = line.substr(last + 1);
  if (version != "HTTP/1.1" && version != "HTTP/1.0") return State::Malformed;
  const std::string_view target = line.substr(first + 1, last - first - 1);
  if (target.empty() || target.front() != '/' || target.find(' ') != std::string_view::npos)
    return State::Malformed;
  method_ = std::string(line.substr(0, first));
  target_ = std::string(target.substr(0, target.find('?')));
  return State::Complete;
}

}  // namespace server
