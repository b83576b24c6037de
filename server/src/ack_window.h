#pragma once
// A client's window of unacknowledged snapshots, and, for a client that left
// view.window unset, its growth with the round trip: the snapshots sent during one
// round trip are all unacknowledged at once, so a fixed window of w snapshots holds
// a client whose round trip exceeds w snapshot periods below the tick rate. The
// round trip is the least time from a snapshot's send to its Ack over the last two
// seconds (a minimum: queueing and jitter only add to it). Socket-free; time is
// passed in.
#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>

namespace server {

class AckWindow {
 public:
  using time_point = std::chrono::steady_clock::time_point;

  struct Sizing {
    std::chrono::nanoseconds snapshot_period{0};  // tick period x snapshot interval; 0: fixed
    std::uint32_t cap = 0;                        // --max-snapshot-window
  };

  // `floor`: the view's window (the default 12 when the Hello left it out).
  // `adapts`: whether the window may grow above it.
  AckWindow(std::uint32_t floor, bool adapts, Sizing sizing);

  void sent(std::uint64_t tick, time_point at);
  // Forgets every snapshot up to `tick` (the caller has checked that it was sent).
  void acked(std::uint64_t tick, time_point at);

  std::size_t unacknowledged() const { return sent_.size(); }
  bool open() const { return sent_.size() < window(); }
  std::uint32_t window() const;
  std::optional<std::chrono::nanoseconds> round_trip() const { return least_; }

 private:
  struct Sent {
    std::uint64_t tick;
    time_point at;
  };
  struct Sample {
    time_point at;
    std::chrono::nanoseconds round_trip;
  };
  static constexpr std::chrono::seconds kRoundTripMemory{2};
  static constexpr std::size_t kMaxSamples = 256;

  std::uint32_t floor_;
  bool adapts_;
  Sizing sizing_;
  std::deque<Sent> sent_;                          // ascending ticks, at most the window
  std::deque<Sample> samples_;                     // the last kRoundTripMemory, at most kMaxSamples
  std::optional<std::chrono::nanoseconds> least_;  // the least round trip of samples_
};

}  // namespace server
