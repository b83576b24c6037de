#pragma once
// The end of a soak run: the server's recording replayed in-process, and every state
// hash a client received compared with the replay's hash for that tick.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

namespace soak {

struct ReplayCheck {
  bool read = false;
  std::string error;
  std::uint64_t ticks = 0;
  std::uint64_t recorded_mismatches = 0;  // the recording's own hashes against the replay
  std::uint64_t client_compared = 0;      // client hashes compared with the replay
  std::uint64_t client_mismatches = 0;
  std::uint64_t client_unreplayed = 0;  // ticks a client saw that the replay never reached
};

// Replays the recording at `path`; `seen` holds the hash clients received, by tick.
ReplayCheck replay_and_compare(const std::filesystem::path& path,
                               const std::map<std::uint64_t, std::uint64_t>& seen);

}  // namespace soak
