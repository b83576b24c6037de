#include "wire/reconstruction.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace wire {
namespace {

enum class RecordKind : std::uint8_t { Quantized, Velocity, Exact };

struct Record {
  std::uint64_t id = 0;
  RecordKind kind = RecordKind::Quantized;
  double x = 0.0;  // exact: the value; quantized: the integer, as a double
  double y = 0.0;
  double vx = 0.0;
  double vy = 0.0;
  bool has_mode = false;
  PredictorMode mode = PredictorMode::Ballistic;
};

// Reads one record list's modes: (gap << 2) | mode, the gap being the record's
// index minus the index of the entry before (the first: the index itself).
template <class Message>
std::string read_modes(const Message& list, std::size_t first, std::vector<Record>& records) {
  const std::uint64_t count = static_cast<std::uint64_t>(list.id_gaps_size());
  std::uint64_t index = 0;
  bool first_entry = true;
  for (const std::uint32_t entry : list.modes()) {
    const std::uint32_t gap = entry >> 2;
    const std::uint32_t mode = entry & 3u;
    if (mode >= kPredictorModeCount) return "a predictor mode out of range";
    if (!first_entry && gap == 0) return "predictor modes are not in ascending record order";
    index += gap;
    first_entry = false;
    if (index >= count) return "a predictor mode names no record";
    records[first + index].has_mode = true;
    records[first + index].mode = static_cast<PredictorMode>(mode);
  }
  return "";
}

std::string read_quantized(const physics::wire::QuantizedBodies& list,
                           std::vector<Record>& records) {
  const int n = list.id_gaps_size();
  if (list.dx_size() != n || list.dy_size() != n || list.dvx_size() != n || list.dvy_size() != n) {
    return "quantized body lists of different lengths";
  }
  std::vector<std::uint64_t> ids;
  if (!decode_id_gaps(list.id_gaps(), ids)) return "quantized body ids do not ascend";
  const std::size_t first = records.size();
  for (int i = 0; i < n; ++i) {
    Record r;
    r.id = ids[static_cast<std::size_t>(i)];
    r.x = static_cast<double>(list.dx(i));
    r.y = static_cast<double>(list.dy(i));
    r.vx = static_cast<double>(list.dvx(i));
    r.vy = static_cast<double>(list.dvy(i));
    records.push_back(r);
  }
  return read_modes(list, first, records);
}

std::string read_velocities(const physics::wire::VelocityBodies& list,
                            std::vector<Record>& records) {
  const int n = list.id_gaps_size();
  if (list.dvx_size() != n || list.dvy_size() != n) return "velocity lists of different lengths";
  std::vector<std::uint64_t> ids;
  if (!decode_id_gaps(list.id_gaps(), ids)) return "velocity record ids do not ascend";
  const std::size_t first = records.size();
  for (int i = 0; i < n; ++i) {
    Record r;
    r.id = ids[static_cast<std::size_t>(i)];
    r.kind = RecordKind::Velocity;
    r.vx = static_cast<double>(list.dvx(i));
    r.vy = static_cast<double>(list.dvy(i));
    records.push_back(r);
  }
  return read_modes(list, first, records);
}

std::string read_exact(const physics::wire::ExactBodies& list, std::vector<Record>& records) {
  const int n = list.id_gaps_size();
  if (list.x_size() != n || list.y_size() != n || list.vx_size() != n || list.vy_size() != n) {
    return "exact body lists of different lengths";
  }
  std::vector<std::uint64_t> ids;
  if (!decode_id_gaps(list.id_gaps(), ids)) return "exact body ids do not ascend";
  const std::size_t first = records.size();
  for (int i = 0; i < n; ++i) {
    Record r;
    r.id = ids[static_cast<std::size_t>(i)];
    r.kind = RecordKind::Exact;
    r.x = list.x(i);
    r.y = list.y(i);
    r.vx = list.vx(i);
    r.vy = list.vy(i);
    if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.vx) ||
        !std::isfinite(r.vy)) {
      return "an exact body state that is not finite";
    }
    records.push_back(r);
  }
  return read_modes(list, first, records);
}

// ENCODING_FULL's bodies: exact values the client holds as they are (mode Hold), so
// that the full encoding has a view hash as the others do.
std::string read_full_bodies(
    const google::protobuf::RepeatedPtrField<physics::wire::BodyState>& list,
    std::vector<Record>& records) {
  bool first = true;
  std::uint64_t last = 0;
  for (const physics::wire::BodyState& state : list) {
    if (!first && state.body_id() <= last) return "full-encoding body ids do not ascend";
    first = false;
    last = state.body_id();
    Record r;
    r.id = state.body_id();
    r.kind = RecordKind::Exact;
    r.x = state.x();
    r.y = state.y();
    r.vx = state.vx();
    r.vy = state.vy();
    r.has_mode = true;
    r.mode = PredictorMode::Hold;
    if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.vx) ||
        !std::isfinite(r.vy)) {
      return "a full-encoding body state that is not finite";
    }
    records.push_back(r);
  }
  return "";
}

// The record applied to what the client held (or to the zero state for a body it
// did not hold): quantized  x = x_predicted + n * quantum;  velocity  the same for
// vx and vy alone;  exact  x = the value.
PredictedBody applied(const Record& r, const PredictedBody* held, Quantum q) {
  PredictedBody body;
  body.id = r.id;
  if (held != nullptr) body = *held;
  switch (r.kind) {
    case RecordKind::Exact:
      body.x = r.x;
      body.y = r.y;
      body.vx = r.vx;
      body.vy = r.vy;
      break;
    case RecordKind::Quantized:
      body.x = body.x + r.x * q.position;
      body.y = body.y + r.y * q.position;
      body.vx = body.vx + r.vx * q.velocity;
      body.vy = body.vy + r.vy * q.velocity;
      break;
    case RecordKind::Velocity:
      body.vx = body.vx + r.vx * q.velocity;
      body.vy = body.vy + r.vy * q.velocity;
      break;
  }
  if (r.has_mode) body.mode = r.mode;
  return body;
}

void mix(std::uint64_t& hash, std::uint64_t word) {
  hash ^= word;
  hash *= kViewHashPrime;
}

}  // namespace

bool decode_id_gaps(const google::protobuf::RepeatedField<std::uint64_t>& gaps,
                    std::vector<std::uint64_t>& ids) {
  ids.clear();
  ids.reserve(static_cast<std::size_t>(gaps.size()));
  std::uint64_t id = 0;
  bool first = true;
  for (const std::uint64_t gap : gaps) {
    if (!first && gap == 0) return false;
    if (gap > std::numeric_limits<std::uint64_t>::max() - id) return false;
    id += gap;
    ids.push_back(id);
    first = false;
  }
  return true;
}

std::string Reconstruction::apply(const physics::wire::Snapshot& snapshot,
                                  const Predictor& predictor, Quantum quantum) {
  // Everything is read and checked before anything changes.
  if (started_ && !snapshot.full() && snapshot.tick() < tick_) {
    return "snapshot tick " + std::to_string(snapshot.tick()) + " is before the last, " +
           std::to_string(tick_);
  }
  if (started_ && !snapshot.full() && snapshot.tick() - tick_ > kMaxTickGap) {
    return "snapshot tick jumps by more than " + std::to_string(kMaxTickGap) + " ticks";
  }
  std::vector<Record> records;
  if (snapshot.has_quantized()) {
    if (std::string error = read_quantized(snapshot.quantized(), records); !error.empty()) {
      return error;
    }
  }
  if (snapshot.has_velocities()) {
    if (std::string error = read_velocities(snapshot.velocities(), records); !error.empty()) {
      return error;
    }
  }
  if (snapshot.has_exact()) {
    if (std::string error = read_exact(snapshot.exact(), records); !error.empty()) return error;
  }
  if (std::string error = read_full_bodies(snapshot.bodies(), records); !error.empty()) {
    return error;
  }
  std::vector<std::uint64_t> gone;
  if (!decode_id_gaps(snapshot.left_gaps(), gone)) return "left body ids do not ascend";
  // Quantized, velocity, exact records, then full-encoding bodies, each list ascending: one list
  // sorted by id (stable, so a body in several lists gets its records in that order).
  std::stable_sort(records.begin(), records.end(),
                   [](const Record& a, const Record& b) { return a.id < b.id; });

  if (snapshot.full()) clear();
  if (!started_) {
    tick_ = snapshot.tick();
    started_ = true;
  }
  advance_to(snapshot.tick(), predictor);

  std::vector<PredictedBody> next;
  next.reserve(bodies_.size() + records.size());
  std::size_t r = 0;
  std::size_t g = 0;
  for (const PredictedBody& held : bodies_) {
    while (r < records.size() && records[r].id < held.id) {
      next.push_back(applied(records[r++], nullptr, quantum));
    }
    while (g < gone.size() && gone[g] < held.id) ++g;
    const bool leaves = g < gone.size() && gone[g] == held.id;
    if (r < records.size() && records[r].id == held.id) {
      PredictedBody body = held;
      while (r < records.size() && records[r].id == held.id) {
        body = applied(records[r++], &body, quantum);
      }
      if (!leaves) next.push_back(body);
    } else if (!leaves) {
      next.push_back(held);
    }
  }
  while (r < records.size()) next.push_back(applied(records[r++], nullptr, quantum));
  // Two records of one new body: keep the last.
  // (unique on the reversed list keeps each id's last, gathered at the back.)
  const auto kept =
      std::unique(next.rbegin(), next.rend(),
                  [](const PredictedBody& a, const PredictedBody& b) { return a.id == b.id; });
  next.erase(next.begin(), kept.base());
  bodies_ = std::move(next);
  return "";
}

void Reconstruction::advance_to(std::uint64_t tick, const Predictor& predictor) {
  if (tick <= tick_) return;
  const std::uint64_t steps = tick - tick_;
  for (PredictedBody& body : bodies_) {
    if (body.mode == PredictorMode::Hold) continue;
    for (std::uint64_t i = 0; i < steps; ++i) predictor.advance(body);
  }
  tick_ = tick;
}

void Reconstruction::clear() {
  bodies_.clear();
  started_ = false;
  tick_ = 0;
}

const PredictedBody* Reconstruction::find(std::uint64_t id) const {
  const auto it =
      std::lower_bound(bodies_.begin(), bodies_.end(), id,
                       [](const PredictedBody& b, std::uint64_t v) { return b.id < v; });
  return it != bodies_.end() && it->id == id ? &*it : nullptr;
}

std::uint64_t Reconstruction::hash() const {
  std::uint64_t hash = kViewHashBasis;
  for (const PredictedBody& b : bodies_) {
    mix(hash, b.id);
    mix(hash, std::bit_cast<std::uint64_t>(b.x));
    mix(hash, std::bit_cast<std::uint64_t>(b.y));
    mix(hash, std::bit_cast<std::uint64_t>(b.vx));
    mix(hash, std::bit_cast<std::uint64_t>(b.vy));
    mix(hash, static_cast<std::uint64_t>(b.mode));
  }
  return hash;
}

}  // namespace wire
