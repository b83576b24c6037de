#pragma once
// physics-server's flags (server/server_cli.h): declared on a CLI11 app, then turned
// into a ServerConfig.
#include <CLI/CLI.hpp>
#include <string>

#include "server/server.h"

namespace server {

struct ServerFlags {
  ServerConfig config;
  std::string scene_file;
  std::string rules_file;
  double tick_rate = 0.0;
  int lockstep_timeout_ms = 250;
  long idle_timeout_ms = 10000;
  long handshake_timeout_ms = 2000;
  std::string token;
  std::string token_file;
  std::string ticket_key_file;
  long hello_backoff_ms = 1000;
  long hello_backoff_max_ms = 60000;
  long seat_backoff_ms = 2000;
  std::string log_level = "info";
  std::string log_format = "text";
  std::string lockstep_pace = "realtime";
  int port = 7777;
  int metrics_port = -1;
  int ws_port = -1;
  long stats_interval_s = 60;
};

// Declares every flag on `app`; --rules too when `offer_rules`.
void add_server_flags(CLI::App& app, ServerFlags& flags, bool offer_rules);

// Completes flags.config from the parsed flags, the files they name (token, ticket
// key) and the environment (PHYSICS_TOKEN, AGONES_SDK_HTTP_PORT). Empty, or what was
// wrong.
std::string finish_server_config(ServerFlags& flags);

}  // namespace server
