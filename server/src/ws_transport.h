#pragma once
// Which port a connection came in on, and what that changes: its Session's framing
// (tcp_framing.h or ws_framing.h), and how a connection refused at accept is told.
#include <memory>
#include <string>

#include "framing.h"
#include "session.h"

namespace server {

enum class Transport { Tcp, WebSocket };

std::unique_ptr<Framing> make_framing(Transport transport, const SessionLimits& limits);

// The WebSocket port's refusal at accept, before any upgrade: an HTTP 429 carrying
// the same text as the TCP port's Error.
std::string ws_refusal_response(const std::string& text);

}  // namespace server
