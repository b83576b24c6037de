#include "ws_client_framing.h"

#include <deque>
#include <utility>
#include <websocketpp/client.hpp>
#include <websocketpp/config/core_client.hpp>

namespace itest {
namespace {

struct Config : websocketpp::config::core_client {
  typedef Config type;
  typedef websocketpp::config::core_client base;
  static const websocketpp::log::level elog_level = websocketpp::log::elevel::none;
  static const websocketpp::log::level alog_level = websocketpp::log::alevel::none;
};

using Endpoint = websocketpp::client<Config>;
using Connection = Endpoint::connection_type;

}  // namespace

struct WsClientFraming::Impl {
  Endpoint endpoint;
  Connection::ptr connection;
  std::string output;
  std::deque<Received> received;
  bool opened = false;
  bool failed = false;
};

WsClientFraming::WsClientFraming(const std::string& uri) : impl_(std::make_unique<Impl>()) {
  Impl& impl = *impl_;
  websocketpp::lib::error_code ec;
  impl.connection = impl.endpoint.get_connection(uri, ec);
  if (ec) {
    impl.failed = true;
    return;
  }
  Connection& con = *impl.connection;
  con.set_write_handler([&impl](websocketpp::connection_hdl, char const* data, size_t size) {
    impl.output.append(data, size);
    return websocketpp::lib::error_code();
  });
  con.set_open_handler([&impl](websocketpp::connection_hdl) { impl.opened = true; });
  con.set_fail_handler([&impl](websocketpp::connection_hdl) { impl.failed = true; });
  con.set_message_handler([&impl](websocketpp::connection_hdl, Connection::message_ptr message) {
    impl.received.push_back(Received{message->get_opcode() == websocketpp::frame::opcode::binary,
                                     message->get_payload()});
  });
  impl.endpoint.connect(impl.connection);
}

WsClientFraming::~WsClientFraming() {
  if (impl_->connection) impl_->connection->fatal_error();
}

void WsClientFraming::feed(const char* data, std::size_t size) {
  if (!impl_->connection) return;
  impl_->connection->read_all(data, size);
}

std::string WsClientFraming::take_output() { return std::exchange(impl_->output, std::string()); }

bool WsClientFraming::open() const {
  return impl_->opened && impl_->connection->get_state() == websocketpp::session::state::open;
}

bool WsClientFraming::failed() const { return impl_->failed; }

bool WsClientFraming::pop(Received& out) {
  if (impl_->received.empty()) return false;
  out = std::move(impl_->received.front());
  impl_->received.pop_front();
  return true;
}

void WsClientFraming::send_binary(const std::string& payload) {
  impl_->connection->send(payload, websocketpp::frame::opcode::binary);
}

void WsClientFraming::send_text(const std::string& payload) {
  impl_->connection->send(payload, websocketpp::frame::opcode::text);
}

void WsClientFraming::ping(const std::string& payload) {
  websocketpp::lib::error_code ignored;
  impl_->connection->ping(payload, ignored);
}

void WsClientFraming::close(std::uint16_t code, const std::string& reason) {
  websocketpp::lib::error_code ignored;
  impl_->connection->close(code, reason, ignored);
}

int WsClientFraming::remote_close_code() const {
  if (!impl_->connection) return 0;
  const auto code = impl_->connection->get_remote_close_code();
  return code == websocketpp::close::status::blank ? 0 : static_cast<int>(code);
}

std::string WsClientFraming::remote_close_reason() const {
  return impl_->connection ? impl_->connection->get_remote_close_reason() : std::string();
}

int WsClientFraming::http_status() const {
  if (!impl_->connection) return 0;
  return static_cast<int>(impl_->connection->get_response_code());
}

}  // namespace itest
