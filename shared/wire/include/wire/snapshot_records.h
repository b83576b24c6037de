#pragma once
// Writes a snapshot's body records as Reconstruction::apply reads them
// (docs/PROTOCOL.md, section 5): three lists (quantized, velocity only, exact), each
// with its ids as gaps from the one before and a mode entry ((index gap << 2) | mode)
// for each record whose predictor mode changes. The server's views write with it;
// the clients only read.
#include <cstddef>
#include <cstdint>

#include "wire.pb.h"
#include "wire/predictor.h"

namespace wire {

// A quantized delta must stay an exact integer in a double on both ends; beyond
// this a body goes as an exact record instead.
inline constexpr double kMaxQuantizedDelta = 4503599627370496.0;  // 2^52

// The size an exact record takes in a snapshot, about (id gap, four doubles, a mode).
inline constexpr std::size_t kExactRecordBytes = 34;

// The size a quantized record of these deltas (in quanta) takes, about: an id gap, a
// mode entry and the four deltas as zigzag varints (9 bytes for one too large).
std::size_t quantized_record_bytes(double dx, double dy, double dvx, double dvy);

class SnapshotRecordWriter {
 public:
  // Writes the records into `snapshot`, whose record lists must be empty.
  explicit SnapshotRecordWriter(physics::wire::Snapshot& snapshot);

  // Each adds one record; records go in ascending id within each list.
  void add_exact(std::uint64_t id, double x, double y, double vx, double vy, bool mode_changes,
                 PredictorMode mode);
  void add_quantized(std::uint64_t id, std::int64_t dx, std::int64_t dy, std::int64_t dvx,
                     std::int64_t dvy, bool mode_changes, PredictorMode mode);
  void add_velocity(std::uint64_t id, std::int64_t dvx, std::int64_t dvy, bool mode_changes,
                    PredictorMode mode);
  // Leaves out of the snapshot the lists no record went into.
  void finish();

  // Where a list's next record's id gap and mode entry are measured from.
  struct ListStart {
    std::uint64_t last_id = 0;
    std::uint32_t last_mode = 0;  // record index of the last mode entry
  };

 private:
  physics::wire::Snapshot& snapshot_;
  physics::wire::QuantizedBodies& quantized_;
  physics::wire::VelocityBodies& velocities_;
  physics::wire::ExactBodies& exact_;
  ListStart quantized_start_;
  ListStart velocity_start_;
  ListStart exact_start_;
};

}  // namespace wire
