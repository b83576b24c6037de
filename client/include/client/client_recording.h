#pragma once
// A client recording (ClientConfig::record_path, physics-client --record,
// docs/REPLAY.md) read back as the client saw it live: the Welcome, then every
// snapshot decoded by the same reconstruction, each with the time it arrived.
// For playing a recorded session again (physics-view --replay) and for comparing
// what two clients were shown.
#include <cstddef>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "client/types.h"

namespace client {

struct RecordedSnapshot {
  Snapshot snapshot;
  double arrival = 0.0;  // s after the client connected
};

struct ClientRecording {
  Welcome welcome;
  std::vector<RecordedSnapshot> snapshots;  // ticks strictly rising
  std::size_t errors = 0;                   // Error messages received
  // A client that reconnected recorded further sessions; only the first is read.
  bool later_sessions = false;
};

// Body states held in memory at most, over all snapshots (about 40 bytes each):
// a longer recording is refused rather than read.
inline constexpr std::size_t kMaxRecordedBodyStates = std::size_t{1} << 23;

// Reads a client recording. On failure, why, naming the byte offset of what is
// refused (a truncated or corrupt file, a server recording, a snapshot that does
// not apply to what came before).
std::variant<ClientRecording, std::string> read_client_recording(const std::filesystem::path& path);
std::variant<ClientRecording, std::string> read_client_recording_bytes(std::string bytes);

}  // namespace client
