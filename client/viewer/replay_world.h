#pragma once
// A client recording played again: the snapshots it holds go through a playout
// buffer as they did live, at the recording's own server times, with pause,
// single steps, speed and seeking.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "client/client_recording.h"
#include "client/playout_buffer.h"
#include "world_shapes.h"
#include "world_source.h"

namespace viewer {

class ReplayWorld : public WorldSource {
 public:
  // `recording` must hold at least one snapshot.
  ReplayWorld(client::ClientRecording recording, std::string name, double speed);

  const client::PlayoutFrame& update(double now) override;
  const WorldShapes& shapes() const override { return shapes_; }
  std::vector<std::string> panel(const client::PlayoutFrame& frame,
                                 std::optional<std::uint64_t> followed) const override;
  // Space pause, '.' and ',' one snapshot on or back, ']' and '[' twice or half
  // the speed, PageDown and PageUp 5 s on or back, Backspace the start.
  bool key(int keycode) override;
  std::string keys_help() const override;

  void set_paused(bool paused) { paused_ = paused; }
  bool paused() const { return paused_; }
  // One snapshot on (+1) or back (-1); pauses.
  void step(int direction);
  // Seeks to a server time (s), within the recording.
  void seek(double server_time);
  // Seeks to the first snapshot whose tick is at least `tick` (the last if none).
  void seek_tick(std::uint64_t tick);
  void set_speed(double speed);
  double speed() const { return speed_; }
  // The snapshot at or before the shown time.
  const client::Snapshot& current() const;
  const client::ClientRecording& recording() const { return recording_; }

 private:
  double time_of(std::size_t index) const;
  std::size_t index_at(double server_time) const;  // last snapshot at or before
  void feed_to(double server_time);
  void restart();

  client::ClientRecording recording_;
  std::string name_;
  client::PlayoutSettings settings_;
  std::optional<client::PlayoutBuffer> buffer_;
  WorldShapes shapes_;
  std::size_t fed_ = 0;  // snapshots pushed into the buffer: [0, fed_)
  double time_ = 0.0;    // the server time shown
  double last_now_ = 0.0;
  bool has_now_ = false;
  double speed_ = 1.0;
  bool paused_ = false;
};

// Shown times within this many ticks of a snapshot's are at that snapshot.
inline constexpr double kSameTime = 1e-6;
inline constexpr double kMinSpeed = 1.0 / 64.0;
inline constexpr double kMaxSpeed = 64.0;

}  // namespace viewer
