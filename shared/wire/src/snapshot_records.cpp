#include "wire/snapshot_records.h"

#include <cmath>

namespace wire {
namespace {

// Starts a record in `list`: its id as a gap from the one before, and a mode entry
// when its mode changes. The caller adds the record's values to the list.
template <class List>
List& start(List& list, SnapshotRecordWriter::ListStart& at, std::uint64_t id, bool mode_changes,
            PredictorMode mode) {
  const auto index = static_cast<std::uint32_t>(list.id_gaps_size());
  list.add_id_gaps(id - at.last_id);
  at.last_id = id;
  if (mode_changes) {
    list.add_modes(((index - at.last_mode) << 2) | static_cast<std::uint32_t>(mode));
    at.last_mode = index;
  }
  return list;
}

std::size_t varint_bytes(std::uint64_t v) {
  std::size_t n = 1;
  for (; v >= 0x80; v >>= 7) ++n;
  return n;
}

std::uint64_t zigzag(std::int64_t v) {
  return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
}

std::size_t quantized_bytes(double d) {
  if (!(std::fabs(d) < kMaxQuantizedDelta)) return 9;
  return varint_bytes(zigzag(static_cast<std::int64_t>(std::nearbyint(d))));
}

}  // namespace

std::size_t quantized_record_bytes(double dx, double dy, double dvx, double dvy) {
  return 3 + quantized_bytes(dx) + quantized_bytes(dy) + quantized_bytes(dvx) +
         quantized_bytes(dvy);
}

SnapshotRecordWriter::SnapshotRecordWriter(physics::wire::Snapshot& snapshot)
    : snapshot_(snapshot),
      quantized_(*snapshot.mutable_quantized()),
      velocities_(*snapshot.mutable_velocities()),
      exact_(*snapshot.mutable_exact()) {}

void SnapshotRecordWriter::add_exact(std::uint64_t id, double x, double y, double vx, double vy,
                                     bool mode_changes, PredictorMode mode) {
  physics::wire::ExactBodies& list = start(exact_, exact_start_, id, mode_changes, mode);
  list.add_x(x);
  list.add_y(y);
  list.add_vx(vx);
  list.add_vy(vy);
}

void SnapshotRecordWriter::add_quantized(std::uint64_t id, std::int64_t dx, std::int64_t dy,
                                         std::int64_t dvx, std::int64_t dvy, bool mode_changes,
                                         PredictorMode mode) {
  physics::wire::QuantizedBodies& list =
      start(quantized_, quantized_start_, id, mode_changes, mode);
  list.add_dx(dx);
  list.add_dy(dy);
  list.add_dvx(dvx);
  list.add_dvy(dvy);
}

void SnapshotRecordWriter::add_velocity(std::uint64_t id, std::int64_t dvx, std::int64_t dvy,
                                        bool mode_changes, PredictorMode mode) {
  physics::wire::VelocityBodies& list = start(velocities_, velocity_start_, id, mode_changes, mode);
  list.add_dvx(dvx);
  list.add_dvy(dvy);
}

void SnapshotRecordWriter::finish() {
  if (quantized_.id_gaps_size() == 0) snapshot_.clear_quantized();
  if (exact_.id_gaps_size() == 0) snapshot_.clear_exact();
  if (velocities_.id_gaps_size() == 0) snapshot_.clear_velocities();
}

}  // namespace wire
