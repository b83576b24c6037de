// libFuzzer harness: the snapshot decoder, wire::Reconstruction::apply, fed a
// sequence of Snapshot messages as a hostile server could send them, in any
// encoding, under a predictor and quanta taken from the input. Nothing in a
// snapshot is trusted: a bad one must be refused with a reason and leave the
// reconstruction as it was; a good one must leave the bodies sorted by id, unique,
// and at the snapshot's tick.
// Covered: Reconstruction::apply, advance_to, hash, decode_id_gaps and the
// predictor. The client library around it (framing, Welcome, the buffers) is
// client_fuzz's.
#include <google/protobuf/stubs/logging.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "wire.pb.h"
#include "wire/framing.h"
#include "wire/predictor.h"
#include "wire/reconstruction.h"

namespace {

double read_double(const std::uint8_t* bytes) {
  double value = 0.0;
  std::memcpy(&value, bytes, sizeof value);
  return value;
}

// Tick rates, gravities and quanta as a Welcome may give them: the client takes
// them from the server, so any finite value within the protocol's ranges.
double pick(double raw, double fallback, double low, double high) {
  if (!(raw >= low && raw <= high)) return fallback;
  return raw;
}

void check_invariants(const wire::Reconstruction& held, const physics::wire::Snapshot& snapshot) {
  const auto& bodies = held.bodies();
  for (std::size_t i = 1; i < bodies.size(); ++i) {
    if (bodies[i - 1].id >= bodies[i].id) std::abort();
  }
  if (held.tick() != snapshot.tick()) std::abort();
  for (const wire::PredictedBody& body : bodies) {
    if (static_cast<std::uint32_t>(body.mode) >= wire::kPredictorModeCount) std::abort();
  }
}

}  // namespace

// Input: 40 bytes of setup (tick rate, gravity x and y, position and velocity
// quanta, as doubles), then length-delimited Snapshot messages.
// libprotobuf logs a line for every string field that is not UTF-8; a fuzzer makes
// millions of those.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  google::protobuf::SetLogHandler(nullptr);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr std::size_t kSetup = 5 * sizeof(double);
  if (size < kSetup) return 0;
  const wire::Predictor predictor(pick(read_double(data), 60.0, 1.0, 1000.0),
                                  pick(read_double(data + 8), 0.0, -1000.0, 1000.0),
                                  pick(read_double(data + 16), -10.0, -1000.0, 1000.0));
  const wire::Quantum quantum{pick(read_double(data + 24), 0.001, 1e-9, 1.0),
                              pick(read_double(data + 32), 0.001, 1e-9, 1.0)};
  wire::FrameReader reader(1u << 16);
  reader.feed(std::span<const std::uint8_t>(data + kSetup, size - kSetup));
  wire::Reconstruction held;
  std::string frame;
  while (reader.next(frame) == wire::FrameStatus::Frame) {
    physics::wire::Snapshot snapshot;
    if (!snapshot.ParseFromString(frame)) continue;
    const std::uint64_t hash_before = held.hash();
    const std::uint64_t tick_before = held.tick();
    const std::string problem = held.apply(snapshot, predictor, quantum);
    if (!problem.empty()) {
      if (held.hash() != hash_before || held.tick() != tick_before) std::abort();
      continue;
    }
    check_invariants(held, snapshot);
    (void)held.hash();
  }
  return 0;
}
