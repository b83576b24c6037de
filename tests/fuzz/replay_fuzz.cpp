// libFuzzer harness: a server recording (docs/REPLAY.md) as physics-sim --replay
// reads it: the recording reader (preamble, header, length-prefixed records, with
// its limits) and the replayer, which builds the recorded scene and steps the
// recorded joins, leaves and inputs through the server's Simulation, comparing
// hashes. A bad file must end in BadFile with an offset, never a crash.
// Covered: shared/recording's reader, server/sim/replayer.cpp, the recorded scene's
// conversion (server::from_recorded) and the Simulation it drives. Not covered:
// reading from a file (RecordingReader::open), which tests of the recording cover.
#include <google/protobuf/stubs/logging.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <variant>

#include "replayer.h"

namespace {
// A recording may be valid and long; a few hundred ticks reach every record kind.
constexpr int kMaxTicks = 300;
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  google::protobuf::SetLogHandler(nullptr);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  replay::Replayer::Opened opened =
      replay::Replayer::from_bytes(std::string(reinterpret_cast<const char*>(data), size));
  auto* replayer = std::get_if<std::unique_ptr<replay::Replayer>>(&opened);
  if (replayer == nullptr) {
    (void)std::get<recording::RecordingError>(opened).to_string();
    return 0;
  }
  for (int i = 0; i < kMaxTicks; ++i) {
    const replay::Replayer::Step step = (*replayer)->step();
    if (step == replay::Replayer::Step::BadFile) {
      (void)(*replayer)->error().to_string();
      break;
    }
    if (step == replay::Replayer::Step::End) break;
    (void)(*replayer)->last_check().diverged();
  }
  return 0;
}
