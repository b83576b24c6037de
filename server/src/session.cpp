#include "session.h"

#include <algorithm>
#include <exception>
#include <utility>

#include "hello_widths.h"
#include "tcp_framing.h"
#include "wire/messages.h"

namespace server {

Session::Session(asio::ip::tcp::socket socket, std::uint32_t id, SessionHost& host,
                 SessionLimits limits, std::unique_ptr<Framing> framing)
    : socket_(std::move(socket)),
      id_(id),
      host_(host),
      limits_(limits),
      framing_(framing ? std::move(framing)
                       : std::make_unique<TcpFraming>(limits.max_message_bytes)),
      byte_bucket_(limits.bytes_per_second, limits.byte_burst, clock::now()),
      message_bucket_(limits.messages_per_second, limits.message_burst, clock::now()),
      full_state_bucket_(limits.full_state_bytes_per_second,
                         2.0 * limits.full_state_bytes_per_second, clock::now()),
      resume_timer_(socket_.get_executor()),
      accepted_(clock::now()),
      last_received_(accepted_) {
  // The frame limit until the session has joined.
  framing_->set_max_message_bytes(std::min(limits.max_hello_bytes, limits.max_message_bytes));
  std::error_code ec;
  // A snapshot must not wait for Nagle's algorithm to gather more bytes.
  socket_.set_option(asio::ip::tcp::no_delay(true), ec);
  if (limits_.socket_send_buffer_bytes > 0) {
    socket_.set_option(asio::socket_base::send_buffer_size(limits_.socket_send_buffer_bytes), ec);
  }
  const auto endpoint = socket_.remote_endpoint(ec);
  address_ = ec ? std::string("unknown") : endpoint.address().to_string();
  peer_ = ec ? address_ : address_ + ":" + std::to_string(endpoint.port());
}

Session::~Session() = default;

void Session::start() { do_read(); }

bool Session::must_pause_reading(clock::time_point now) {
  if (closing_) return false;  // draining discards input: no limit to apply
  return frames_held_ || byte_bucket_.in_debt(now);
}

// A pause ends when its cause does: control messages written (do_write resumes), or
// the buckets refilled (a timer).
void Session::schedule_resume(clock::time_point now) {
  if (resume_armed_ || closed_) return;
  if (queued_control() >= limits_.pause_reading_at_control) return;
  const auto wait = std::max(byte_bucket_.wait(now), message_bucket_.wait(now));
  if (wait <= clock::duration::zero()) {
    // Nothing owed: held frames wait only for the queue, which is below its mark.
    resume_armed_ = true;
    asio::post(socket_.get_executor(), [self = shared_from_this()] {
      self->resume_armed_ = false;
      self->resume();
    });
    return;
  }
  host_.on_throttled(*this);
  resume_armed_ = true;
  resume_timer_.expires_after(wait);
  resume_timer_.async_wait([self = shared_from_this()](std::error_code ec) {
    self->resume_armed_ = false;
    if (!ec) self->resume();
  });
}

void Session::resume() {
  if (closed_) return;
  if (frames_held_ && !closing_) handle_frames();
  do_read();
}

void Session::do_read() {
  // One read at a time; none while an Error is still being written before a close,
  // and after it only to drain what the client still sends (see begin_draining).
  if (reading_ || closed_ || (closing_ && !draining_)) return;
  const auto now = clock::now();
  if (must_pause_reading(now)) {
    schedule_resume(now);
    return;
  }
  reading_ = true;
  socket_.async_read_some(asio::buffer(read_buffer_), [self = shared_from_this()](
                                                          std::error_code ec, std::size_t bytes) {
    self->reading_ = false;
    if (self->closed_) return;
    if (ec) {
      self->finish(self->closing_ ? self->close_reason_ : DropReason::Disconnected);
      return;
    }
    self->on_read(bytes);
  });
}

void Session::on_read(std::size_t bytes) {
  last_received_ = clock::now();
  received_any_ = received_any_ || bytes > 0;
  host_.on_bytes(0, bytes);
  byte_bucket_.spend(static_cast<double>(bytes), last_received_);
  if (!closing_) {
    framing_->feed(read_buffer_.data(), bytes);
    handle_frames();
  }
  do_read();
}

void Session::begin_draining() {
  // The Error is written. Closing now with unread bytes in our receive buffer would
  // send a reset, which can destroy the Error before the client reads it; instead
  // send FIN and discard input until the client closes (or close_linger passes).
  draining_ = true;
  std::error_code ignored;
  socket_.shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
  do_read();
}

void Session::handle_frames() {
  std::string frame;
  frames_held_ = false;
  while (!closing_) {
    // Over the message rate, or replies piling up: leave the rest of the frames in
    // the reader (at most one read's worth) and read nothing more until resumed.
    const auto now = clock::now();
    if (queued_control() >= limits_.pause_reading_at_control || message_bucket_.in_debt(now)) {
      frames_held_ = true;
      return;
    }
    switch (framing_->next(frame)) {
      case Framing::Status::NeedMore:
        flush_output();
        return;
      case Framing::Status::Control:
        // A WebSocket ping or pong (answered by the framing): a message, for the rate.
        flush_output();
        message_bucket_.spend(1.0, now);
        continue;
      case Framing::Status::TooLarge:
        close_with_error(physics::wire::ERROR_MESSAGE_TOO_LARGE, frame,
                         DropReason::MessageTooLarge);
        return;
      case Framing::Status::Malformed:
        close_with_error(physics::wire::ERROR_MALFORMED, frame, DropReason::Malformed);
        return;
      case Framing::Status::PeerClosed:
        close_when_written(DropReason::Disconnected);
        return;
      case Framing::Status::Message:
        flush_output();
        break;
    }
    physics::wire::ClientMessage message;
    if (!wire::parse_client_message(frame, message)) {
      close_with_error(
          physics::wire::ERROR_MALFORMED,
          "a frame of " + std::to_string(frame.size()) + " bytes does not parse as a ClientMessage",
          DropReason::Malformed);
      return;
    }
    message_bucket_.spend(1.0, now);
    if (message.has_hello()) {
      if (const std::optional<WideField> wide = find_wide_hello_field(frame)) {
        close_with_error(wide->code, wide->text, wide->reason);
        return;
      }
    }
    // A message handler that throws (std::bad_alloc, say) takes down this session only: every
    // other session and the tick loop go on.
    try {
      host_.on_message(*this, message);
    } catch (const std::exception& error) {
      host_.on_handler_failed(*this, error.what());
      close_with_error(physics::wire::ERROR_INTERNAL,
                       "the server failed handling this connection's message; closing it",
                       DropReason::InternalError);
      return;
    }
  }
}

void Session::send(const physics::wire::ServerMessage& message) {
  if (closing_ || closed_) return;
  const std::size_t control = queue_.size() - waiting_snapshots_;
  if (control >= limits_.max_queued_control) {
    // Pongs and Errors piled up unread: the client does not read what it asks for.
    close_now(DropReason::TooSlow);
    return;
  }
  Outgoing item;
  item.bytes = encode(message);
  enqueue(std::move(item));
}

std::string Session::encode(const physics::wire::ServerMessage& message) const {
  const std::string payload = message.SerializeAsString();
  return framing_->header(payload.size()) + payload;
}

void Session::flush_output() {
  std::string output = framing_->take_output();
  if (output.empty()) return;
  Outgoing item;
  item.bytes = std::move(output);
  enqueue(std::move(item));
}

void Session::send_snapshot(std::shared_ptr<const std::string> shared, std::string tail) {
  if (closing_ || closed_) return;
  if (waiting_snapshots_ >= limits_.max_queued_snapshots) {
    close_now(DropReason::TooSlow);
    return;
  }
  Outgoing item;
  item.snapshot = std::move(shared);
  item.tail = std::move(tail);
  ++waiting_snapshots_;
  enqueue(std::move(item));
}

void Session::enqueue(Outgoing item) {
  queue_.push_back(std::move(item));
  if (!in_flight_) do_write();
}

void Session::do_write() {
  if (in_flight_ || closed_) return;
  if (queue_.empty()) {
    if (closing_ && finish_when_written_) {
      finish(close_reason_);
    } else if (closing_ && !draining_) {
      begin_draining();
    }
    return;
  }
  in_flight_ = std::make_unique<Outgoing>(std::move(queue_.front()));
  queue_.pop_front();
  write_started_ = clock::now();
  Outgoing& item = *in_flight_;
  std::size_t count = 1;
  if (item.snapshot) {
    --waiting_snapshots_;
    const std::size_t snapshot_bytes = item.snapshot->size() + item.tail.size();
    const std::string message_header = snapshot_message_header(snapshot_bytes);
    item.bytes = framing_->header(message_header.size() + snapshot_bytes) + message_header;
    item.buffers[1] = asio::buffer(*item.snapshot);
    item.buffers[2] = asio::buffer(item.tail);
    count = 3;
  }
  item.buffers[0] = asio::buffer(item.bytes);
  asio::async_write(
      socket_, std::span<const asio::const_buffer>(item.buffers.data(), count),
      [self = shared_from_this()](std::error_code ec, std::size_t written) {
        if (self->closed_) return;
        self->host_.on_bytes(written, 0);
        if (ec) {
          self->finish(self->closing_ ? self->close_reason_ : DropReason::Disconnected);
          return;
        }
        self->in_flight_.reset();
        self->do_write();
        // Replies written: frames held for want of room may go on.
        if (self->frames_held_) self->schedule_resume(clock::now());
      });
}

void Session::close_with_error(physics::wire::ErrorCode code, const std::string& text,
                               DropReason reason) {
  if (closing_ || closed_) return;
  drop_waiting_snapshots();
  Outgoing item;
  // Before a WebSocket's upgrade, there is no frame to put an Error in.
  if (framing_->open()) item.bytes = encode(wire::make_error(code, text, true));
  framing_->close();
  item.bytes += framing_->take_output();
  closing_ = true;
  close_reason_ = reason;
  close_deadline_ = clock::now() + limits_.close_linger;
  if (item.bytes.empty()) {
    do_write();  // nothing to write: on to draining
  } else {
    enqueue(std::move(item));
  }
  announce_closing(reason);
}

void Session::drop_waiting_snapshots() {
  // Waiting snapshots are of no use to a client that is being closed.
  for (auto it = queue_.begin(); it != queue_.end();) {
    if (it->snapshot) {
      it = queue_.erase(it);
      --waiting_snapshots_;
    } else {
      ++it;
    }
  }
}

void Session::close_when_written(DropReason reason) {
  if (closing_ || closed_) return;
  drop_waiting_snapshots();
  closing_ = true;
  close_reason_ = reason;
  finish_when_written_ = true;
  close_deadline_ = clock::now() + limits_.close_linger;
  announce_closing(reason);
  framing_->close();
  flush_output();
  do_write();
}

void Session::announce_closing(DropReason reason) {
  if (announced_closing_) return;
  announced_closing_ = true;
  host_.on_closing(*this, reason);
}

void Session::close_now(DropReason reason) {
  if (closed_) return;
  closing_ = true;
  close_reason_ = reason;
  finish(reason);
}

void Session::check_deadlines(clock::time_point now) {
  if (closed_) return;
  if (closing_) {
    if (now >= close_deadline_) finish(close_reason_);
    return;
  }
  if (!joined_ && now - accepted_ >= limits_.handshake_timeout) {
    close_with_error(physics::wire::ERROR_TOO_SLOW,
                     "no Hello within " + std::to_string(limits_.handshake_timeout.count()) +
                         " ms of connecting",
                     DropReason::HandshakeTimeout);
    return;
  }
  if (in_flight_ && now - write_started_ >= limits_.idle_timeout) {
    // The client has read nothing for idle_timeout: an Error could not reach it.
    close_now(DropReason::TooSlow);
    return;
  }
  if (now - last_received_ >= limits_.idle_timeout) {
    close_with_error(physics::wire::ERROR_TOO_SLOW,
                     "nothing received for " + std::to_string(limits_.idle_timeout.count()) +
                         " ms (send Ping when there is no input to send)",
                     DropReason::Idle);
  }
}

void Session::finish(DropReason reason) {
  if (closed_) return;
  closed_ = true;
  closing_ = true;
  std::error_code ignored;
  socket_.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
  queue_.clear();
  waiting_snapshots_ = 0;
  resume_timer_.cancel();
  announce_closing(reason);
  host_.on_closed(*this, reason);
}

}  // namespace server
