// The WebSocket port: its listening socket, its accept loop (each connection then
// admitted exactly as on the TCP port: server_connections.cpp), and its framing.
#include "ws_transport.h"

#include <spdlog/spdlog.h>

#include <stdexcept>
#include <system_error>

#include "server_impl.h"
#include "tcp_framing.h"
#include "ws_framing.h"

namespace server {

std::unique_ptr<Framing> make_framing(Transport transport, const SessionLimits& limits) {
  if (transport == Transport::WebSocket) {
    return std::make_unique<WsFraming>(limits.max_message_bytes);
  }
  return std::make_unique<TcpFraming>(limits.max_message_bytes);
}

std::string ws_refusal_response(const std::string& text) {
  return "HTTP/1.1 429 Too Many Requests\r\nConnection: close\r\nContent-Type: text/plain\r\n"
         "Content-Length: " +
         std::to_string(text.size()) + "\r\n\r\n" + text;
}

void Server::Impl::listen_ws(const asio::ip::address& address, std::uint16_t port) {
  const std::string where = config_.bind + ":" + std::to_string(port);
  const asio::ip::tcp::endpoint endpoint(address, port);
  std::error_code ec;
  ws_acceptor_.emplace(io_);
  ws_acceptor_->open(endpoint.protocol(), ec);
  if (!ec) ws_acceptor_->set_option(asio::ip::tcp::acceptor::reuse_address(true), ec);
  if (!ec) ws_acceptor_->bind(endpoint, ec);
  if (!ec) ws_acceptor_->listen(asio::socket_base::max_listen_connections, ec);
  if (ec) throw std::system_error(ec, "cannot listen for WebSocket on " + where);
  ws_port_ = ws_acceptor_->local_endpoint().port();
}

void Server::Impl::do_ws_accept() {
  ws_acceptor_->async_accept([this](std::error_code ec, asio::ip::tcp::socket socket) {
    if (stopping_ || ec == asio::error::operation_aborted) return;
    if (ec) {
      // Out of descriptors, typically: wait a little rather than spin on the error.
      spdlog::warn("WebSocket accept failed: {}", ec.message());
      ws_accept_retry_timer_.expires_after(std::chrono::milliseconds(100));
      ws_accept_retry_timer_.async_wait([this](std::error_code wait_error) {
        if (!wait_error && !stopping_) do_ws_accept();
      });
      return;
    }
    admit(std::move(socket), Transport::WebSocket);
    do_ws_accept();
  });
}

void Server::Impl::close_ws_acceptor() {
  std::error_code ignored;
  if (ws_acceptor_) ws_acceptor_->close(ignored);
  ws_accept_retry_timer_.cancel();
}

}  // namespace server
