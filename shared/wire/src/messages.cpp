#include "wire/messages.h"

#include <limits>
#include <utility>

namespace wire {
namespace {

namespace pb = physics::wire;

bool parse(std::string_view bytes, google::protobuf::MessageLite& out) {
  // ParseFromArray takes an int: a longer buffer would wrap to a negative size.
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    out.Clear();
    return false;
  }
  // ParseFromArray also fails on invalid UTF-8 in proto3 strings, which is wanted:
  // such bytes are malformed.
  return out.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()));
}

}  // namespace

pb::ServerMessage make_error(pb::ErrorCode code, std::string message, bool fatal) {
  pb::ServerMessage envelope;
  auto* error = envelope.mutable_error();
  error->set_code(code);
  error->set_message(std::move(message));
  error->set_fatal(fatal);
  return envelope;
}

pb::ClientMessage make_hello(std::string client_name, HelloOptions options) {
  pb::ClientMessage envelope;
  auto* hello = envelope.mutable_hello();
  hello->set_protocol_version(options.protocol_version);
  hello->set_client_name(std::move(client_name));
  hello->set_access_token(std::move(options.access_token));
  // A message that serializes to no bytes holds only defaults.
  if (options.view.ByteSizeLong() != 0) *hello->mutable_view() = std::move(options.view);
  hello->set_spectate(options.spectate);
  hello->set_want_world(options.want_world);
  hello->set_run_rules(options.run_rules);
  hello->set_sensor_events(options.sensor_events);
  if (options.seat) hello->set_seat(*options.seat);
  if (options.contacts) *hello->mutable_contacts() = std::move(*options.contacts);
  return envelope;
}

pb::ClientMessage make_hello(std::string client_name, std::string access_token,
                             std::uint32_t protocol_version) {
  HelloOptions options;
  options.access_token = std::move(access_token);
  options.protocol_version = protocol_version;
  return make_hello(std::move(client_name), std::move(options));
}

pb::ClientMessage make_input(std::uint64_t tick, double ax, double ay, std::uint64_t sequence) {
  pb::ClientMessage envelope;
  auto* input = envelope.mutable_input();
  input->set_tick(tick);
  input->set_ax(ax);
  input->set_ay(ay);
  input->set_sequence(sequence);
  return envelope;
}

pb::ClientMessage make_ack(std::uint64_t tick) {
  pb::ClientMessage envelope;
  envelope.mutable_ack()->set_tick(tick);
  return envelope;
}

pb::ClientMessage make_ping(std::uint64_t nonce, std::uint64_t client_time_ns) {
  pb::ClientMessage envelope;
  auto* ping = envelope.mutable_ping();
  ping->set_nonce(nonce);
  ping->set_client_time_ns(client_time_ns);
  return envelope;
}

pb::ClientMessage make_bye(std::string reason) {
  pb::ClientMessage envelope;
  envelope.mutable_bye()->set_reason(std::move(reason));
  return envelope;
}

pb::ClientMessage make_full_state_request() {
  pb::ClientMessage envelope;
  envelope.mutable_full_state_request();
  return envelope;
}

bool parse_client_message(std::string_view bytes, pb::ClientMessage& out) {
  return parse(bytes, out);
}

bool parse_server_message(std::string_view bytes, pb::ServerMessage& out) {
  return parse(bytes, out);
}

std::string_view error_code_name(pb::ErrorCode code) { return pb::ErrorCode_Name(code); }

}  // namespace wire
