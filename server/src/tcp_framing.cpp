#include "tcp_framing.h"

namespace server {

Framing::Status TcpFraming::next(std::string& out) {
  switch (reader_.next(out)) {
    case wire::FrameStatus::NeedMore:
      return Status::NeedMore;
    case wire::FrameStatus::Frame:
      return Status::Message;
    case wire::FrameStatus::TooLarge:
      out = "message of " + std::to_string(reader_.rejected_length()) +
            " bytes is over the limit of " + std::to_string(reader_.max_message_bytes()) + " bytes";
      return Status::TooLarge;
    case wire::FrameStatus::BadPrefix:
      break;
  }
  out = "length prefix is not a valid varint (over 10 bytes or 64 bits)";
  return Status::Malformed;
}

std::string TcpFraming::header(std::size_t payload_bytes) const {
  std::string prefix;
  wire::append_varint_prefix(payload_bytes, prefix);
  return prefix;
}

}  // namespace server
