#include "client/client_recording.h"

#include "convert.h"
#include "recording/recording_file.h"
#include "wire.pb.h"
#include "wire/messages.h"
#include "wire/reconstruction.h"

namespace client {
namespace {

std::string at(std::uint64_t offset, const std::string& message) {
  return "offset " + std::to_string(offset) + ": " + message;
}

std::variant<ClientRecording, std::string> decode(const recording::LoadedRecording& file) {
  if (!file.header.has_client())
    return at(file.header_offset, "not a client recording (its header is not a ClientRun)");
  ClientRecording out;
  bool welcomed = false;
  wire::Reconstruction reconstruction;
  wire::Predictor predictor;
  wire::Quantum quantum;
  bool has_applied_input = false;
  std::uint64_t last_applied_input_tick = 0;
  bool in_sync = true;                       // as of the last snapshot that carried a view hash
  std::vector<std::uint64_t> kinematic_ids;  // ascending (convert::note_kinematic)
  std::size_t states = 0;
  for (std::size_t i = 0; i < file.records.size(); ++i) {
    const physics::recording::Record& record = file.records[i];
    const std::uint64_t offset = file.offsets[i];
    if (!record.has_received()) return at(offset, "a record that is not a received message");
    physics::wire::ServerMessage message;
    if (!wire::parse_server_message(record.received().server_message(), message))
      return at(offset, "a received message that does not parse as a ServerMessage");
    const double arrival = static_cast<double>(record.received().micros()) / 1e6;
    if (message.has_welcome()) {
      if (welcomed) {
        out.later_sessions = true;
        break;
      }
      welcomed = true;
      out.welcome = convert::from_wire(message.welcome());
      if (!(out.welcome.tick_rate > 0.0))
        return at(offset, "a Welcome whose tick_rate is not positive");
      predictor =
          wire::Predictor(out.welcome.tick_rate, out.welcome.gravity.x, out.welcome.gravity.y);
      quantum = {out.welcome.view.position_precision, out.welcome.view.velocity_precision};
      kinematic_ids.clear();
      convert::note_kinematic(kinematic_ids, out.welcome.bodies, {});
      continue;
    }
    if (message.has_error()) {
      ++out.errors;
      continue;
    }
    if (!message.has_snapshot()) continue;  // Pongs, and kinds newer than ours
    if (!welcomed) return at(offset, "a Snapshot before the Welcome");
    const physics::wire::Snapshot& wire_snapshot = message.snapshot();
    Snapshot snapshot = convert::header_from_wire(wire_snapshot);
    if (!out.snapshots.empty() && snapshot.tick <= out.snapshots.back().snapshot.tick)
      return at(offset, "a Snapshot whose tick " + std::to_string(snapshot.tick) +
                            " is not after the one before");
    if (wire_snapshot.has_applied_input()) has_applied_input = true;
    if (wire_snapshot.last_applied_input_tick() != 0)
      last_applied_input_tick = wire_snapshot.last_applied_input_tick();
    snapshot.has_applied_input = has_applied_input;
    snapshot.last_applied_input_tick = last_applied_input_tick;
    const std::string problem = reconstruction.apply(wire_snapshot, predictor, quantum);
    if (!problem.empty()) return at(offset, "a Snapshot that does not apply: " + problem);
    snapshot.records = static_cast<std::size_t>(
        wire_snapshot.quantized().id_gaps_size() + wire_snapshot.velocities().id_gaps_size() +
        wire_snapshot.exact().id_gaps_size() + wire_snapshot.bodies_size());
    convert::note_kinematic(kinematic_ids, snapshot.added, snapshot.removed);
    convert::bodies_held(reconstruction, kinematic_ids, snapshot.bodies);
    if (wire_snapshot.has_view_hash()) in_sync = reconstruction.hash() == wire_snapshot.view_hash();
    snapshot.in_sync = in_sync;
    if (!out.welcome.spectator) {
      if (const BodyState* own = snapshot.find(out.welcome.body_id)) snapshot.own = *own;
    }
    snapshot.wire_bytes = record.received().server_message().size();
    states += snapshot.bodies.size();
    if (states > kMaxRecordedBodyStates)
      return at(offset, "more than " + std::to_string(kMaxRecordedBodyStates) +
                            " body states in all: too long a recording to hold");
    out.snapshots.push_back({std::move(snapshot), arrival});
  }
  if (!welcomed) return at(file.header_offset, "no Welcome: the client never joined");
  return out;
}

template <class Loaded>
std::variant<ClientRecording, std::string> from(Loaded loaded) {
  if (const auto* error = std::get_if<recording::RecordingError>(&loaded))
    return error->to_string();
  return decode(std::get<recording::LoadedRecording>(loaded));
}

}  // namespace

std::variant<ClientRecording, std::string> read_client_recording(
    const std::filesystem::path& path) {
  return from(recording::load_recording(path));
}

std::variant<ClientRecording, std::string> read_client_recording_bytes(std::string bytes) {
  return from(recording::load_recording_bytes(std::move(bytes)));
}

}  // namespace client
