#include "wire/view_settings.h"

#include <algorithm>
#include <cmath>

namespace wire {
namespace {

bool in_range(double value, double low, double high) {
  return std::isfinite(value) && value >= low && value <= high;
}

std::string range_text(const char* field, double low, double high) {
  return std::string("view.") + field + " must be a finite number in [" + std::to_string(low) +
         ", " + std::to_string(high) + "]";
}

}  // namespace

bool ViewSettings::operator==(const ViewSettings& o) const {
  return encoding == o.encoding && quantum.position == o.quantum.position &&
         quantum.velocity == o.quantum.velocity && position_tolerance == o.position_tolerance &&
         velocity_tolerance == o.velocity_tolerance && snapshot_interval == o.snapshot_interval &&
         window == o.window && window_adapts == o.window_adapts && interest == o.interest &&
         interest_radius == o.interest_radius && interest_rect.min_x() == o.interest_rect.min_x() &&
         interest_rect.min_y() == o.interest_rect.min_y() &&
         interest_rect.max_x() == o.interest_rect.max_x() &&
         interest_rect.max_y() == o.interest_rect.max_y() && byte_budget == o.byte_budget &&
         state_hash == o.state_hash && view_hash_interval == o.view_hash_interval;
}

// One check per ViewRequest field in the message's order: as long as the message is.
std::string resolve_view(const physics::wire::ViewRequest& request, std::uint32_t max_window,
                         ViewSettings& out) {
  ViewSettings s;
  if (!physics::wire::Encoding_IsValid(request.encoding())) {
    return "view.encoding " + std::to_string(request.encoding()) + " is not a known encoding";
  }
  s.encoding = request.encoding();
  if (request.has_position_precision()) s.quantum.position = request.position_precision();
  if (request.has_velocity_precision()) s.quantum.velocity = request.velocity_precision();
  if (!in_range(s.quantum.position, kMinPrecision, kMaxPrecision)) {
    return range_text("position_precision", kMinPrecision, kMaxPrecision);
  }
  if (!in_range(s.quantum.velocity, kMinPrecision, kMaxPrecision)) {
    return range_text("velocity_precision", kMinPrecision, kMaxPrecision);
  }
  // The default tolerances (1 cm, 0.1 m/s) never fall below one quantum.
  s.position_tolerance = request.has_position_tolerance()
                             ? request.position_tolerance()
                             : std::fmax(s.position_tolerance, s.quantum.position);
  s.velocity_tolerance = request.has_velocity_tolerance()
                             ? request.velocity_tolerance()
                             : std::fmax(s.velocity_tolerance, s.quantum.velocity);
  if (!in_range(s.position_tolerance, s.quantum.position, kMaxTolerance)) {
    return range_text("position_tolerance (at least position_precision)", s.quantum.position,
                      kMaxTolerance);
  }
  if (!in_range(s.velocity_tolerance, s.quantum.velocity, kMaxTolerance)) {
    return range_text("velocity_tolerance (at least velocity_precision)", s.quantum.velocity,
                      kMaxTolerance);
  }
  if (request.has_snapshot_interval()) {
    s.snapshot_interval = request.snapshot_interval();
    if (s.snapshot_interval < 1 || s.snapshot_interval > kMaxSnapshotInterval) {
      return "view.snapshot_interval must be in [1, " + std::to_string(kMaxSnapshotInterval) +
             "] ticks, got " + std::to_string(s.snapshot_interval);
    }
  }
  const std::uint32_t window_limit = max_window < 1 ? 1 : max_window;
  s.window = std::min(s.window, window_limit);
  s.window_adapts = !request.has_window();
  if (request.has_window()) {
    s.window = request.window();
    if (s.window < 1 || s.window > window_limit) {
      return "view.window must be in [1, " + std::to_string(window_limit) + "] snapshots, got " +
             std::to_string(s.window);
    }
  }
  if (request.has_interest_radius()) {
    s.interest = InterestKind::Radius;
    s.interest_radius = request.interest_radius();
    if (!std::isfinite(s.interest_radius) || s.interest_radius <= 0.0 ||
        s.interest_radius > kMaxInterestRadius) {
      return "view.interest_radius must be finite, > 0 and at most " +
             std::to_string(kMaxInterestRadius) + " m";
    }
  } else if (request.has_interest_rect()) {
    s.interest = InterestKind::Rect;
    s.interest_rect = request.interest_rect();
    const auto& r = s.interest_rect;
    const double m = kMaxInterestCoordinate;
    if (!in_range(r.min_x(), -m, m) || !in_range(r.min_y(), -m, m) || !in_range(r.max_x(), -m, m) ||
        !in_range(r.max_y(), -m, m) || !(r.min_x() < r.max_x()) || !(r.min_y() < r.max_y())) {
      return "view.interest_rect must be finite, within +-1e9 m, with min < max on both axes";
    }
  }
  if (request.has_byte_budget()) {
    s.byte_budget = request.byte_budget();
    if (s.byte_budget != 0 && (s.byte_budget < kMinByteBudget || s.byte_budget > kMaxByteBudget)) {
      return "view.byte_budget must be 0 (none) or in [" + std::to_string(kMinByteBudget) + ", " +
             std::to_string(kMaxByteBudget) + "] bytes";
    }
  }
  s.state_hash = request.state_hash();
  if (request.has_view_hash_interval()) {
    s.view_hash_interval = request.view_hash_interval();
    if (s.view_hash_interval < 1 || s.view_hash_interval > kMaxViewHashInterval) {
      return "view.view_hash_interval must be in [1, " + std::to_string(kMaxViewHashInterval) +
             "] snapshots, got " + std::to_string(s.view_hash_interval);
    }
  }
  out = s;
  return "";
}

physics::wire::ViewRequest to_wire(const ViewSettings& s) {
  physics::wire::ViewRequest w;
  w.set_encoding(s.encoding);
  w.set_position_precision(s.quantum.position);
  w.set_velocity_precision(s.quantum.velocity);
  w.set_position_tolerance(s.position_tolerance);
  w.set_velocity_tolerance(s.velocity_tolerance);
  w.set_snapshot_interval(s.snapshot_interval);
  w.set_window(s.window);
  if (s.interest == InterestKind::Radius) w.set_interest_radius(s.interest_radius);
  if (s.interest == InterestKind::Rect) *w.mutable_interest_rect() = s.interest_rect;
  w.set_byte_budget(s.byte_budget);
  w.set_state_hash(s.state_hash);
  w.set_view_hash_interval(s.view_hash_interval);
  return w;
}

}  // namespace wire
