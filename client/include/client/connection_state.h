#pragma once
// The client's connection states, as in yojimbo: negative values are failures
// (the connection is closed), zero is idle, positive values are progress towards
// and in a session. docs/PROTOCOL.md draws the transitions.
#include <cstdint>

namespace client {

enum class ConnectionState : std::int8_t {
  ConnectionLost = -6,   // the server closed a session, or a socket error ended it
  ProtocolError = -5,    // the server sent bytes we cannot frame or parse
  Refused = -4,          // the server answered Hello with an Error (see last_error)
  WelcomeTimedOut = -3,  // connected, sent Hello, no Welcome or Error in time
  ConnectTimedOut = -2,  // no TCP connection in time
  ConnectFailed = -1,    // TCP connect failed (bad address, connection refused)
  Disconnected = 0,      // idle: never connected, or left with Bye
  Connecting = 1,        // TCP connect in progress
  AwaitingWelcome = 2,   // Hello sent, waiting for Welcome or Error
  Connected = 3,         // Welcome received: inputs go out, snapshots come in
};

const char* to_string(ConnectionState state);
inline bool is_failure(ConnectionState state) { return static_cast<int>(state) < 0; }

}  // namespace client
