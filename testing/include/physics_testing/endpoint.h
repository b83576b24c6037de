#pragma once
// Where a server under test listens, and client configs that point at it.
#include <cstdint>
#include <string>
#include <string_view>

#include "client/client.h"

namespace physics_testing {

struct Endpoint {
  std::string host = "127.0.0.1";
  std::uint16_t port = 0;
  std::string token;  // the server's access token, "" when it needs none

  // A client config for this server with the client library's defaults.
  client::ClientConfig client_config(const std::string& name = "test-client") const;
  // The same, asking for exact state and the world's state hash in every snapshot:
  // for comparing a networked run with an in-process one bit for bit.
  client::ClientConfig exact_client_config(const std::string& name = "test-client") const;
};

// The address to connect to for a server bound to `bind`: the loopback address for
// the wildcards 0.0.0.0 and ::, `bind` itself otherwise.
std::string connectable_host(std::string_view bind);

}  // namespace physics_testing
