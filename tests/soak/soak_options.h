#pragma once
// physics-soak's flags: the scene, the mode, how long, how many client slots, the
// seed of the script, and where the recording and the CSV line go.
#include <cstdint>
#include <string>

#include "client/client.h"

namespace soak {

struct Options {
  std::string scene_file = "scenes/moving-1000.textproto";
  bool lockstep = false;
  double duration = 60.0;
  double warmup = 10.0;
  int clients = 64;
  std::uint64_t seed = 1;
  std::string record_path;  // empty: a temporary file, removed at the end
  std::string csv_path;
  client::Encoding encoding = client::Encoding::Predicted;
};

}  // namespace soak
