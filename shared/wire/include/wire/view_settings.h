#pragma once
// A client's view settings (Hello.view): the defaults, the ranges, and the one
// function that turns a ViewRequest into settings or says which field is wrong.
// The server applies it to every Hello; a client's bad setting is reported by the
// server's refusal (ERROR_INVALID_VIEW), which names the field.
#include <cstdint>
#include <string>

#include "wire.pb.h"
#include "wire/reconstruction.h"

namespace wire {

enum class InterestKind : std::uint8_t { World, Radius, Rect };

struct ViewSettings {
  physics::wire::Encoding encoding = physics::wire::ENCODING_PREDICTED;
  Quantum quantum{};  // 1 mm, 1 mm/s
  double position_tolerance = 0.01;
  double velocity_tolerance = 0.1;
  std::uint32_t snapshot_interval = 1;
  std::uint32_t window = 12;
  // The Hello left the window out: the server may widen it to cover the client's
  // round trip (docs/PROTOCOL.md 5.8), never past --max-snapshot-window.
  bool window_adapts = true;
  InterestKind interest = InterestKind::World;
  double interest_radius = 0.0;
  physics::wire::Rect interest_rect;
  std::uint32_t byte_budget = 0;  // 0: no budget
  bool state_hash = false;
  // The view hash in every k-th snapshot with body news (and in all others): a
  // client finds a desync at most k snapshots after the one that caused it.
  std::uint32_t view_hash_interval = 4;

  bool operator==(const ViewSettings& other) const;
};

// Ranges (docs/PROTOCOL.md, section 5.1).
inline constexpr double kMinPrecision = 1e-9;
inline constexpr double kMaxPrecision = 1.0;
inline constexpr double kMaxTolerance = 1000.0;
inline constexpr std::uint32_t kMaxSnapshotInterval = 1000;
inline constexpr std::uint32_t kMaxWindow = 256;
inline constexpr double kMaxInterestRadius = 1e6;
inline constexpr double kMaxInterestCoordinate = 1e9;
inline constexpr std::uint32_t kMinByteBudget = 64;
inline constexpr std::uint32_t kMaxByteBudget = 1u << 20;
inline constexpr std::uint32_t kMaxViewHashInterval = 1000;

// Fills `out` from `request` (absent fields: the defaults; the window is capped at
// `max_window`). Returns "" or a sentence naming the field at fault and its range.
std::string resolve_view(const physics::wire::ViewRequest& request, std::uint32_t max_window,
                         ViewSettings& out);
// Every field filled in, as Welcome.view carries it.
physics::wire::ViewRequest to_wire(const ViewSettings& settings);

}  // namespace wire
