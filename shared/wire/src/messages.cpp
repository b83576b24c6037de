#include "wire/messages.h"

#include <utility>

namespace wire {

physics::wire::ServerMessage make_error(physics::wire::ErrorCode code, std::string message,
                                        bool fatal) {
  physics::wire::ServerMessage envelope;
  auto* error = envelope.mutable_error();
  error->set_code(code);
  error->set_message(std::move(message));
  error->set_fatal(fatal);
  return envelope;
}

physics::wire::ClientMessage make_hello(std::string client_name, std::string access_token,
                                        std::uint32_t protocol_version) {
  physics::wire::ClientMessage envelope;
  auto* hello = envelope.mutable_hello();
  hello->set_protocol_version(protocol_version);
  hello->set_client_name(std::move(client_name));
  hello->set_access_token(std::move(access_token));
  return envelope;
}

physics::wire::ClientMessage make_input(std::uint64_t tick, double ax, double ay,
                                        std::uint64_t sequence) {
  physics::wire::ClientMessage envelope;
  auto* input = envelope.mutable_input();
  input->set_tick(tick);
  input->set_ax(ax);
  input->set_ay(ay);
  input->set_sequence(sequence);
  return envelope;
}

bool parse_client_message(std::string_view bytes, physics::wire::ClientMessage& out) {
  // ParseFromArray also fails on invalid UTF-8 in proto3 strings, which is wanted:
  // such bytes are malformed.
  return out.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()));
}

bool parse_server_message(std::string_view bytes, physics::wire::ServerMessage& out) {
  return out.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()));
}

std::string_view error_code_name(physics::wire::ErrorCode code) {
  return physics::wire::ErrorCode_Name(code);
}

}  // namespace wire
