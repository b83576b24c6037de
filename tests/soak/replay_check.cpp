// The replay check: the recording stepped again by the server's own tick logic,
// tick by tick against the recorded hashes and the clients' hashes.
#include "replay_check.h"

#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <variant>

#include "replayer.h"

namespace soak {

ReplayCheck replay_and_compare(const std::filesystem::path& path,
                               const std::map<std::uint64_t, std::uint64_t>& seen) {
  ReplayCheck result;
  auto opened = replay::Replayer::open(path);
  if (auto* error = std::get_if<recording::RecordingError>(&opened)) {
    result.error = error->to_string();
    return result;
  }
  replay::Replayer& replayer = *std::get<std::unique_ptr<replay::Replayer>>(opened);
  for (;;) {
    const replay::Replayer::Step step = replayer.step();
    if (step == replay::Replayer::Step::BadFile) {
      result.error = replayer.error().to_string();
      return result;
    }
    if (step == replay::Replayer::Step::End) break;
    const replay::TickCheck& check = replayer.last_check();
    ++result.ticks;
    if (check.diverged()) ++result.recorded_mismatches;
    if (const auto it = seen.find(check.tick); it != seen.end()) {
      ++result.client_compared;
      if (it->second != check.replayed_hash) {
        if (result.client_mismatches == 0) {
          fmt::print(stderr,
                     "physics-soak: DESYNC at tick {}: a client got {:016x}, replay {:016x}\n",
                     check.tick, it->second, check.replayed_hash);
        }
        ++result.client_mismatches;
      }
    }
  }
  for (const auto& [tick, hash] : seen) {
    if (tick > replayer.tick()) ++result.client_unreplayed;
  }
  result.read = true;
  return result;
}

}  // namespace soak
