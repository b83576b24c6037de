#pragma once
// A playout buffer: snapshot interpolation (Fiedler, "Snapshot Interpolation").
//
// Snapshots go in as they arrive, each with its arrival time on the caller's clock
// (seconds, any origin; tests pass a fake clock). state_at(now) returns every body
// at a server time a little in the past,
//
//   shown = estimated newest server time now - delay,
//   delay = send_intervals * send_interval + jitter_multiplier * jitter,
//           clamped to [min_delay, max_delay],
//
// interpolating linearly between the two snapshots around it, so that late or
// uneven arrivals do not show as stutter. The newest server time now is `now - offset`,
// offset being the smallest (arrival - server time) among the snapshots held: the
// fastest transit seen recently. jitter is RFC 3550's smoothed mean of
// |D|, D the change in transit time between consecutive snapshots (gain 1/16).
//
// The shown time moves with the caller's clock and is steered toward its target
// at most `slew` seconds per second (10%), so that a change of delay never makes
// the picture jump; a target further than `snap` away (a reset, the first frame)
// is jumped to. Between two snapshots more than one send interval apart (a world
// at rest sends a heartbeat a second; a slow reader skips ticks) the earlier one
// is carried forward at its velocity until one interval before the later one,
// then interpolated: for the exact encodings a tick not sent is a tick on which
// nothing changed. Past the newest snapshot each body is extrapolated at its
// velocity for at most max_extrapolation seconds, then held.
//
// Bounds: at most `capacity` snapshots are held (the oldest is dropped). A snapshot
// with a tick not after the newest one's is refused, as is one with a NaN or
// infinite state or arrival time. An arrival time before the previous one is taken
// as the previous one (counted). A snapshot more than max_gap seconds of server
// time after the newest empties the buffer and starts again from it (counted).
// Between two frames, the shown time never moves by more than (1 + slew) times the
// caller's clock, except on a snap; so a body moving at speed v jumps at most
// (1 + slew) * v * frame time, plus what its own velocity changed.
//
// One thread at a time; no allocation beyond the snapshots held and the frame.
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "client/types.h"

namespace client {

struct PlayoutSettings {
  // The server's tick rate (Welcome::tick_rate): a tick's server time is tick / rate.
  double tick_rate = 60.0;
  // The time between two snapshots the server sends, nominally (s): the view's
  // snapshot_interval / tick_rate. 0: one tick.
  double send_interval = 0.0;
  double send_intervals = 3.0;      // intervals of delay: covers two lost snapshots
  double jitter_multiplier = 3.0;   // times the measured jitter added on top
  double min_delay = 0.0;           // s
  double max_delay = 1.0;           // s
  double max_extrapolation = 0.25;  // s past the newest snapshot; then held
  double slew = 0.1;                // s of correction per s of clock, at most
  double snap = 1.0;                // s: a target further away is jumped to
  double max_gap = 5.0;             // s of server time: a larger gap resets
  std::size_t capacity = 64;        // snapshots held, at least 2

  // Empty when every field is in range; otherwise what is wrong, for a person.
  std::string validate() const;
};

enum class PushResult : std::uint8_t {
  Accepted,
  Reset,     // accepted after emptying the buffer (a gap over max_gap)
  Stale,     // refused: its tick is not after the newest snapshot's
  BadTime,   // refused: the arrival time is NaN or infinite
  BadState,  // refused: a position or velocity is NaN or infinite
};

const char* to_string(PushResult result);

enum class PlayoutStatus : std::uint8_t {
  Empty,          // no snapshot yet: no bodies
  Early,          // the shown time is before the oldest snapshot held: it is shown
  Interpolating,  // between two snapshots
  Extrapolating,  // past the newest, within max_extrapolation
  Holding,        // past the newest by more than max_extrapolation: held there
};

const char* to_string(PlayoutStatus status);

struct PlayoutBody {
  std::uint64_t body_id = 0;
  Vec2 position;
  Vec2 velocity;
  // Its state is the same, bit for bit, in the two newest snapshots held: nothing
  // moved it between them (with the exact encodings: it is asleep or at rest).
  bool still = false;
  Motion motion = Motion::Dynamic;  // the snapshot's BodyState::motion
};

struct PlayoutFrame {
  PlayoutStatus status = PlayoutStatus::Empty;
  double server_time = 0.0;   // s: the server time shown (tick / tick_rate)
  double lag = 0.0;           // s: estimated newest server time now minus server_time
  double extrapolated = 0.0;  // s past the newest snapshot (Extrapolating, Holding)
  std::uint64_t newest_tick = 0;
  std::vector<PlayoutBody> bodies;  // every body of the snapshots around, ascending id
};

struct PlayoutStats {
  std::uint64_t accepted = 0;
  std::uint64_t stale = 0;
  std::uint64_t bad_time = 0;
  std::uint64_t bad_state = 0;
  std::uint64_t resets = 0;
  std::uint64_t clock_backwards = 0;  // arrival or render times before the last one
  std::uint64_t snaps = 0;            // frames whose shown time jumped to its target
  std::uint64_t dropped = 0;          // over capacity
};

class PlayoutBuffer {
 public:
  // Throws std::invalid_argument when settings.validate() is not empty.
  explicit PlayoutBuffer(PlayoutSettings settings);

  PushResult push(const Snapshot& snapshot, double arrival_time);
  // The world at the shown time for the caller's clock reading `now`. A NaN, or a
  // `now` before the previous call's, is taken as the previous call's (counted).
  const PlayoutFrame& state_at(double now);
  // The world at a given server time (s), without the clock: for pictures of one
  // tick (screenshots) and for stepping through a recording. Leaves the shown
  // time that state_at steers unchanged.
  const PlayoutFrame& state_at_server_time(double server_time);

  // The delay the shown time is steered to (s), and its parts.
  double delay() const;
  double jitter() const { return jitter_; }
  // The smallest (arrival - server time) among the snapshots held (s).
  double offset() const { return offset_; }
  std::size_t size() const { return held_.size(); }
  const PlayoutSettings& settings() const { return settings_; }
  const PlayoutStats& stats() const { return stats_; }
  // The newest snapshot held (nullptr when empty), for what is not interpolated
  // (its tick, state hash, shapes added and removed).
  const Snapshot* newest() const { return held_.empty() ? nullptr : &held_.back().snapshot; }

 private:
  struct Held {
    Snapshot snapshot;
    double server_time = 0.0;
    double transit = 0.0;  // arrival - server_time
  };

  void clear();
  void recompute_offset();
  void fill(double shown);
  double interval() const;

  PlayoutSettings settings_;
  std::deque<Held> held_;
  std::vector<std::uint64_t> still_ids_;  // ascending: same state in the two newest
  PlayoutStats stats_;
  double offset_ = 0.0;
  double jitter_ = 0.0;
  double last_arrival_ = 0.0;
  bool has_arrival_ = false;
  double last_now_ = 0.0;
  bool has_now_ = false;
  double shown_ = 0.0;
  bool has_shown_ = false;
  PlayoutFrame frame_;
};

}  // namespace client
