#include "physics_testing/endpoint.h"

namespace physics_testing {

client::ClientConfig Endpoint::client_config(const std::string& name) const {
  client::ClientConfig config;
  config.host = host;
  config.port = port;
  config.name = name;
  config.token = token;
  return config;
}

client::ClientConfig Endpoint::exact_client_config(const std::string& name) const {
  client::ClientConfig config = client_config(name);
  config.view.encoding = client::Encoding::Exact;
  config.view.state_hash = true;
  return config;
}

std::string connectable_host(std::string_view bind) {
  if (bind == "0.0.0.0") return "127.0.0.1";
  if (bind == "::") return "::1";
  return std::string(bind);
}

}  // namespace physics_testing
