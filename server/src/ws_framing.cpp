#include "ws_framing.h"

#include <algorithm>
#include <deque>
#include <utility>
#include <websocketpp/config/core.hpp>
#include <websocketpp/frame.hpp>
#include <websocketpp/server.hpp>

namespace server {
namespace {

// websocketpp's core configuration (no socket, no TLS, no extensions, so no
// permessage-deflate), quiet: the server logs what matters itself.
struct WsConfig : websocketpp::config::core {
  typedef WsConfig type;
  typedef websocketpp::config::core base;
  static const websocketpp::log::level elog_level = websocketpp::log::elevel::none;
  static const websocketpp::log::level alog_level = websocketpp::log::alevel::none;
  // A body after the upgrade request has no use here.
  static const size_t max_http_body_size = 0;
};

using Endpoint = websocketpp::server<WsConfig>;
using Connection = Endpoint::connection_type;
namespace close_status = websocketpp::close::status;

// Bytes handed to the library at a time. Each slice can complete at most
// kSliceBytes / 6 frames (a masked empty ping is 6 bytes), each answered or handed
// out at once; slicing keeps that burst small, so the Session's pause on the message
// rate and on waiting replies works at the same grain as on the TCP port.
constexpr std::size_t kSliceBytes = 512;

}  // namespace

struct WsFraming::Impl {
  struct Event {
    Status status;
    std::string bytes;
  };

  Endpoint endpoint;
  Connection::ptr connection;
  std::string output;   // written by the library, not yet taken
  std::string pending;  // fed, not yet handed to the library
  std::size_t pending_at = 0;
  std::deque<Event> events;
  std::size_t max_message_bytes = 0;
  bool opened = false;
  bool ended = false;      // an end (error, close) was reported: hand out nothing more
  bool we_closed = false;  // close() was called
  close_status::value close_code = close_status::normal;

  void end(Status status, std::string text) {
    if (ended || we_closed) return;
    ended = true;
    events.push_back(Event{status, std::move(text)});
  }

  // After a slice: a close the library began on its own (a protocol error it
  // answered with a close frame), or the peer's close frame.
  void check_closing() {
    if (ended || we_closed || !opened) return;
    const auto state = connection->get_state();
    if (state != websocketpp::session::state::closing &&
        state != websocketpp::session::state::closed) {
      return;
    }
    // The remote code stays abnormal_close (1006, never sent on the wire) until the
    // peer's close frame comes.
    const close_status::value remote = connection->get_remote_close_code();
    if (remote != close_status::abnormal_close && remote != close_status::blank) {
      end(Status::PeerClosed, "closed by the peer");
    } else if (connection->get_local_close_code() == close_status::message_too_big) {
      end(Status::TooLarge, "a message over the limit of " + std::to_string(max_message_bytes) +
                                " bytes (" + connection->get_local_close_reason() + ")");
    } else {
      end(Status::Malformed, "WebSocket protocol error: " + connection->get_local_close_reason());
    }
  }
};

WsFraming::WsFraming(std::size_t max_message_bytes) : impl_(std::make_unique<Impl>()) {
  Impl& impl = *impl_;
  impl.connection = impl.endpoint.get_connection();
  Connection& con = *impl.connection;
  con.set_write_handler([&impl](websocketpp::connection_hdl, char const* data, size_t size) {
    impl.output.append(data, size);
    return websocketpp::lib::error_code();
  });
  con.set_open_handler([&impl](websocketpp::connection_hdl) { impl.opened = true; });
  con.set_fail_handler([&impl](websocketpp::connection_hdl) {
    impl.end(Status::Malformed, "not a WebSocket upgrade: " + impl.connection->get_ec().message());
  });
  con.set_close_handler([&impl](websocketpp::connection_hdl) { impl.check_closing(); });
  con.set_message_handler([&impl](websocketpp::connection_hdl, Connection::message_ptr message) {
    if (impl.ended || impl.we_closed) return;
    if (message->get_opcode() != websocketpp::frame::opcode::binary) {
      impl.close_code = close_status::unsupported_data;
      impl.end(Status::Malformed, "a text frame: send each message as one binary frame");
      return;
    }
    impl.events.push_back(Impl::Event{Status::Message, std::move(message->get_raw_payload())});
  });
  con.set_ping_handler([&impl](websocketpp::connection_hdl, std::string) {
    if (!impl.ended && !impl.we_closed) impl.events.push_back(Impl::Event{Status::Control, {}});
    return true;  // the library answers with a pong
  });
  con.set_pong_handler([&impl](websocketpp::connection_hdl, std::string) {
    if (!impl.ended && !impl.we_closed) impl.events.push_back(Impl::Event{Status::Control, {}});
  });
  set_max_message_bytes(max_message_bytes);
  con.start();
}

WsFraming::~WsFraming() {
  // The library's pending read holds its connection: end it, so that both go.
  impl_->we_closed = true;
  impl_->connection->fatal_error();
}

void WsFraming::feed(const std::uint8_t* data, std::size_t size) {
  Impl& impl = *impl_;
  if (impl.ended || impl.we_closed) return;
  if (impl.pending_at == impl.pending.size()) {
    impl.pending.clear();
    impl.pending_at = 0;
  }
  impl.pending.append(reinterpret_cast<const char*>(data), size);
}

Framing::Status WsFraming::next(std::string& out) {
  Impl& impl = *impl_;
  for (;;) {
    if (!impl.events.empty()) {
      Impl::Event event = std::move(impl.events.front());
      impl.events.pop_front();
      out = std::move(event.bytes);
      return event.status;
    }
    if (impl.ended || impl.we_closed || impl.pending_at == impl.pending.size()) {
      impl.pending.clear();
      impl.pending_at = 0;
      return Status::NeedMore;
    }
    const std::size_t slice = std::min(kSliceBytes, impl.pending.size() - impl.pending_at);
    const std::size_t used =
        impl.connection->read_some(impl.pending.data() + impl.pending_at, slice);
    // Nothing taken: the library reads no more (it failed or closed); the rest is dropped.
    impl.pending_at = used == 0 ? impl.pending.size() : impl.pending_at + used;
    impl.check_closing();
  }
}

void WsFraming::set_max_message_bytes(std::size_t max) {
  impl_->max_message_bytes = max;
  impl_->connection->set_max_message_size(max);
}

// Also while the library closes after a protocol error: its close frame waits in
// `output`, and an Error written before it is still in order.
bool WsFraming::open() const { return impl_->opened && !impl_->we_closed; }

std::string WsFraming::header(std::size_t payload_bytes) const {
  const websocketpp::frame::basic_header basic(websocketpp::frame::opcode::binary, payload_bytes,
                                               true, false);
  const websocketpp::frame::extended_header extended(payload_bytes);
  return websocketpp::frame::prepare_header(basic, extended);
}

std::string WsFraming::take_output() { return std::exchange(impl_->output, std::string()); }

void WsFraming::close() {
  Impl& impl = *impl_;
  if (impl.we_closed) return;
  impl.we_closed = true;
  if (impl.connection->get_state() != websocketpp::session::state::open) return;
  websocketpp::lib::error_code ignored;
  impl.connection->close(impl.close_code, std::string(), ignored);
}

}  // namespace server
