#pragma once
// Writes a server recording (docs/REPLAY.md) as the Simulation runs: joins, leaves,
// every input applied that changed a body's acceleration, and each tick's hash.
// The Simulation calls it only when one is attached, so not recording costs one
// pointer test per event.
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "physics/body.h"
#include "physics/world.h"
#include "recording.pb.h"
#include "recording/recording_file.h"
#include "scene/scene.h"
#include "server/room.h"

namespace server {

struct RecordOptions {
  // The state hash of every tick that is a multiple of this: 1 finds the first
  // tick that differs exactly (docs/REPLAY.md says what each choice costs).
  std::uint32_t hash_every = 1;
  // A hash of every dynamic body at ticks that are multiples of this, so that a
  // replay can name the bodies that differ; 0: never.
  std::uint32_t body_hashes_every = 60;
  bool lockstep = false;  // written in the header, for people
};

class TickRecorder {
 public:
  // Creates `path` and writes the header: the scene, the tick rate stepped and the
  // input window. nullptr and *error when the file cannot be written.
  static std::unique_ptr<TickRecorder> create(const std::filesystem::path& path,
                                              const scene::SceneDef& scene, double tick_rate,
                                              std::uint64_t max_ticks_ahead, RecordOptions options,
                                              std::string* error);
  ~TickRecorder();

  // `tick` is the last tick stepped when it happened.
  void joined(std::uint64_t tick, ClientId client, phys::BodyId body,
              std::optional<std::uint32_t> seat);
  void left(std::uint64_t tick, ClientId client);
  // The acceleration `client`'s body holds from `tick` on; written only when it
  // differs from the last one written for that client.
  void applied(std::uint64_t tick, ClientId client, phys::Vec2 acceleration);
  // A game message delivered to the rules at `tick` (before it is stepped).
  void game_message(std::uint64_t tick, ClientId client, const std::string& payload);
  // After `tick` was stepped.
  void stepped(std::uint64_t tick, const phys::World& world);

  // False once a write failed (the recording then stops growing; the run goes on).
  bool ok() const { return writer_->ok(); }
  std::uint64_t bytes_written() const { return writer_->bytes_written(); }
  bool flush() { return writer_->flush(); }

 private:
  TickRecorder(std::unique_ptr<recording::RecordingWriter> writer, RecordOptions options);
  std::unique_ptr<recording::RecordingWriter> writer_;
  RecordOptions options_;
  std::map<ClientId, phys::Vec2> last_written_;
  physics::recording::Record record_;  // reused, so that a tick allocates nothing new
};

}  // namespace server
