#pragma once
// The bodies a client holds: what it was sent, carried forward by the predictor.
// The client library keeps one per session; the server keeps one per view, built by
// the same apply() from the same messages, so both hold the same bits
// (docs/PROTOCOL.md, section 5). Bodies are kept sorted by id.
#include <cstdint>
#include <string>
#include <vector>

#include "wire.pb.h"
#include "wire/predictor.h"

namespace wire {

// The quanta of QuantizedBodies: a record's integer n stands for n * quantum.
struct Quantum {
  double position = 0.001;
  double velocity = 0.001;
};

// A snapshot may carry the bodies this far ahead of the last one; a larger jump is
// refused, so that a hostile server cannot make a client step forever.
inline constexpr std::uint64_t kMaxTickGap = 1u << 22;

class Reconstruction {
 public:
  // Applies one snapshot: `full` clears first; every body is advanced to the
  // snapshot's tick; the bodies in left_gaps go; records (and the full encoding's
  // bodies, held in mode Hold) replace or add bodies.
  // Returns "" on success, or what was wrong with the snapshot (nothing is
  // trusted: sizes, order, ranges and gaps are checked before anything changes).
  std::string apply(const physics::wire::Snapshot& snapshot, const Predictor& predictor,
                    Quantum quantum);
  // Advances every body one predictor step per tick up to `tick` (>= tick()).
  void advance_to(std::uint64_t tick, const Predictor& predictor);
  void clear();

  std::uint64_t tick() const { return tick_; }
  bool started() const { return started_; }
  const std::vector<PredictedBody>& bodies() const { return bodies_; }
  const PredictedBody* find(std::uint64_t id) const;
  // FNV-1a over 64-bit words, for each body in ascending id: id, the bit patterns of
  // x, y, vx, vy, then the mode. Snapshot.view_hash is this after the snapshot.
  std::uint64_t hash() const;

 private:
  std::vector<PredictedBody> bodies_;
  std::uint64_t tick_ = 0;
  bool started_ = false;
};

// FNV-1a's 64-bit offset basis and prime, as the view hash uses them.
inline constexpr std::uint64_t kViewHashBasis = 0xcbf29ce484222325ull;
inline constexpr std::uint64_t kViewHashPrime = 0x100000001b3ull;

// Decodes ascending ids sent as gaps (the first is the id itself). False when an id
// does not rise or overflows 64 bits.
bool decode_id_gaps(const google::protobuf::RepeatedField<std::uint64_t>& gaps,
                    std::vector<std::uint64_t>& ids);

}  // namespace wire
