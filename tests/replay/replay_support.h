#pragma once
// What the replay tests share: a temporary file per test, and the records of a
// recording by kind.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "physics/vec2.h"
#include "recording.pb.h"
#include "recording/recording_file.h"
#include "server/game_rules.h"
#include "server/tick_recorder.h"

namespace rtest {

// A path in the test's temporary directory, removed when this goes.
class TempFile {
 public:
  explicit TempFile(const std::string& name);
  ~TempFile();
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::string bytes() const;

 private:
  std::filesystem::path path_;
};

// Loads a recording that must be readable (a test failure otherwise, and empty).
recording::LoadedRecording load_or_fail(const std::filesystem::path& path);
std::size_t count_kind(const recording::LoadedRecording& loaded,
                       physics::recording::Record::KindCase kind);

// Client k's input at tick t: it changes every `hold` ticks, so most ticks repeat
// the last input (and a recording holds only the changes).
phys::Vec2 scripted_input(std::size_t k, std::uint64_t t, std::uint64_t hold = 5);

// A run of the default scene in-process (no sockets): `clients` join at tick 0,
// client k (ids 1..clients) sends scripted_input for every tick up to `ticks`.
// Recorded to `path`; returns the world's hash after each tick (index tick - 1).
// With `rules`, the run has them (server/game_rules.h).
std::vector<std::uint64_t> record_in_process(const std::filesystem::path& path, std::size_t clients,
                                             std::uint64_t ticks,
                                             server::RecordOptions options = {},
                                             std::shared_ptr<server::GameRules> rules = nullptr);

}  // namespace rtest
