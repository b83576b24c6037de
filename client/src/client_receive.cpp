// What a Client does with the bytes the server sends: frames them, parses each
// message, and turns Welcome, Snapshot, Error and Pong into the client's state.
#include <string>
#include <utility>

#include "client/client.h"
#include "client_io.h"
#include "convert.h"
#include "recording/recording_file.h"
#include "wire/messages.h"

namespace client {
namespace {

// Buffered errors and pongs are few in a healthy session; the bound only stops a
// misbehaving server from growing them without limit.
constexpr std::size_t kMaxBufferedSmallEvents = 256;

// Bytes of the base-128 varint that prefixes a frame of `size` bytes.
std::size_t varint_size(std::size_t size) {
  std::size_t bytes = 1;
  for (; size >= 0x80; size >>= 7) ++bytes;
  return bytes;
}

}  // namespace

void Client::start_read() {
  io_->socket.async_read_some(
      asio::buffer(io_->buffer), [this](const std::error_code& error, std::size_t count) {
        if (error == asio::error::operation_aborted) return;
        if (error) {
          if (state_ == ConnectionState::Connected || state_ == ConnectionState::AwaitingWelcome) {
            const bool closed = error == asio::error::eof;
            fail(ConnectionState::ConnectionLost,
                 closed ? std::string(state_ == ConnectionState::Connected
                                          ? "the server closed the connection"
                                          : "the server closed the connection before Welcome")
                        : error.message());
          }
          return;
        }
        on_bytes(count);
      });
}

void Client::on_bytes(std::size_t count) {
  stats_.bytes_received += count;
  io_->reader.feed(std::span<const std::uint8_t>(io_->buffer.data(), count));
  std::string frame;
  for (;;) {
    switch (io_->reader.next(frame)) {
      case wire::FrameStatus::NeedMore:
        start_read();
        return;
      case wire::FrameStatus::TooLarge:
        fail(ConnectionState::ProtocolError,
             "server frame of " + std::to_string(io_->reader.rejected_length()) +
                 " bytes is over the limit of " + std::to_string(config_.max_message_bytes));
        return;
      case wire::FrameStatus::BadPrefix:
        fail(ConnectionState::ProtocolError, "server sent a bad length prefix");
        return;
      case wire::FrameStatus::Frame:
        handle_frame(frame);
        if (is_failure(state_) || state_ == ConnectionState::Disconnected) return;
        break;
    }
  }
}

void Client::handle_frame(const std::string& frame) {
  if (recorder_) {
    physics::recording::Record record;
    physics::recording::Received& received = *record.mutable_received();
    received.set_micros(static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - record_start_)
            .count()));
    received.set_server_message(frame);
    recorder_->append(record);
  }
  physics::wire::ServerMessage message;
  if (!wire::parse_server_message(frame, message)) {
    fail(ConnectionState::ProtocolError, "server sent a message that does not parse");
    return;
  }
  using Kind = physics::wire::ServerMessage::KindCase;
  switch (message.kind_case()) {
    case Kind::kWelcome:
      if (state_ != ConnectionState::AwaitingWelcome) {
        fail(ConnectionState::ProtocolError, "server sent a second Welcome");
        return;
      }
      welcome_ = convert::from_wire(message.welcome());
      held_ = std::make_unique<Held>();
      held_->predictor =
          wire::Predictor(welcome_.tick_rate, welcome_.gravity.x, welcome_.gravity.y);
      held_->quantum = {welcome_.view.position_precision, welcome_.view.velocity_precision};
      convert::note_kinematic(held_->kinematic_ids, welcome_.bodies, {});
      state_ = ConnectionState::Connected;
      return;
    case Kind::kSnapshot:
      if (state_ != ConnectionState::Connected) {
        fail(ConnectionState::ProtocolError, "server sent a Snapshot before Welcome");
        return;
      }
      on_snapshot(message.snapshot(), frame.size() + varint_size(frame.size()));
      return;
    case Kind::kError: {
      ServerError error = convert::from_wire(message.error());
      ++stats_.errors_received;
      if (errors_.size() >= kMaxBufferedSmallEvents) errors_.pop_front();
      errors_.push_back(error);
      if (error.fatal) {
        error_.server = error;
        fail(state_ == ConnectionState::AwaitingWelcome ? ConnectionState::Refused
                                                        : ConnectionState::ConnectionLost,
             "");
      }
      return;
    }
    case Kind::kPong:
      if (pongs_.size() >= kMaxBufferedSmallEvents) pongs_.pop_front();
      pongs_.push_back(convert::from_wire(message.pong()));
      pongs_.back().received_at = Clock::now();
      return;
    case Kind::kGameMessage:
      if (game_messages_.size() >= kMaxBufferedSmallEvents) {
        game_messages_.erase(game_messages_.begin());
      }
      game_messages_.push_back({message.game_message().tick(), message.game_message().payload()});
      return;
    case Kind::KIND_NOT_SET:
      // A kind newer than this client: ignored, as proto3 intends.
      return;
  }
}

void Client::on_snapshot(const physics::wire::Snapshot& message, std::size_t wire_bytes) {
  Held& held = *held_;
  Snapshot snapshot = convert::header_from_wire(message);
  // The input fields come only when they change.
  if (message.has_applied_input()) held.has_applied_input = true;
  if (message.last_applied_input_tick() != 0) {
    held.last_applied_input_tick = message.last_applied_input_tick();
  }
  snapshot.has_applied_input = held.has_applied_input;
  snapshot.last_applied_input_tick = held.last_applied_input_tick;
  const std::string problem = held.reconstruction.apply(message, held.predictor, held.quantum);
  if (!problem.empty()) {
    fail(ConnectionState::ProtocolError, "server sent a snapshot that does not apply: " + problem);
    return;
  }
  snapshot.records = static_cast<std::size_t>(
      message.quantized().id_gaps_size() + message.velocities().id_gaps_size() +
      message.exact().id_gaps_size() + message.bodies_size());
  convert::note_kinematic(held.kinematic_ids, snapshot.added, snapshot.removed);
  convert::bodies_held(held.reconstruction, held.kinematic_ids, snapshot.bodies);
  // A full state: the bodies' (full), or the world's itself (the input relay).
  if (message.full() || !message.world_state().empty()) {
    full_state_asked_ = false;
    ++stats_.full_states_received;
  }
  // The hash comes with every k-th snapshot (view_hash_interval); in between, the
  // last comparison holds.
  if (message.has_view_hash()) {
    held.in_sync = held.reconstruction.hash() == message.view_hash();
    if (!held.in_sync) {
      ++stats_.desyncs;
      if (!full_state_asked_ && !request_full_state()) return;
    }
  }
  snapshot.in_sync = held.in_sync;
  if (!welcome_.spectator) {
    if (const BodyState* own = snapshot.find(welcome_.body_id)) snapshot.own = *own;
  }
  snapshot.received_at = Clock::now();
  snapshot.wire_bytes = wire_bytes;
  ++stats_.snapshots_received;
  stats_.records_received += snapshot.records;
  if (snapshots_.size() >= config_.max_buffered_snapshots) {
    snapshots_.pop_front();
    ++stats_.snapshots_dropped;
  }
  snapshots_.push_back(std::move(snapshot));
}

}  // namespace client
