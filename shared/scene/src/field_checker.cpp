// The checker's machinery: recording the first fault, and the number checks.
#include "field_checker.h"

#include <fmt/format.h>
#include <google/protobuf/stubs/common.h>

#include <cmath>
#include <utility>

namespace scene::detail {

bool Checker::fail(const FieldPath& path, std::string message) {
  const TextLocation where = path.locate(*physics::scene::Scene::descriptor(), locations_);
  error_ = SceneError{std::string(origin_), where.line, where.column, path.to_string(),
                      std::move(message)};
  return false;
}

bool Checker::finite(const FieldPath& path, double value) {
  if (std::isfinite(value)) return true;
  return fail(path, fmt::format("must be a finite number, got {}", value));
}

bool Checker::positive(const FieldPath& path, double value) {
  if (!finite(path, value)) return false;
  if (value > 0.0) return true;
  return fail(path, fmt::format("must be > 0, got {}", value));
}

bool Checker::not_negative(const FieldPath& path, double value) {
  if (!finite(path, value)) return false;
  if (value >= 0.0) return true;
  return fail(path, fmt::format("must be >= 0, got {}", value));
}

bool Checker::at_most(const FieldPath& path, double value, double limit, std::string_view why) {
  if (value <= limit) return true;
  return fail(path, fmt::format("must be at most {} ({}), got {}", limit, why, value));
}

bool Checker::in_range(const FieldPath& path, double value, double low, double high) {
  if (!finite(path, value)) return false;
  if (value >= low && value <= high) return true;
  return fail(path, fmt::format("must be in [{}, {}], got {}", low, high, value));
}

bool Checker::in_range(const FieldPath& path, std::int64_t value, std::int64_t low,
                       std::int64_t high) {
  if (value >= low && value <= high) return true;
  return fail(path, fmt::format("must be in [{}, {}], got {}", low, high, value));
}

bool Checker::finite(const FieldPath& path, const physics::scene::Vec2& value) {
  return finite(path.child("x"), value.x()) && finite(path.child("y"), value.y());
}

bool Checker::coordinate(const FieldPath& path, const physics::scene::Vec2& value) {
  for (const auto& [axis, number] : {std::pair{"x", value.x()}, std::pair{"y", value.y()}}) {
    const FieldPath axis_path = path.child(axis);
    if (!finite(axis_path, number)) return false;
    if (!at_most(axis_path, std::fabs(number), kMaxCoordinate, "largest |coordinate|"))
      return false;
  }
  return true;
}

// Names travel to clients in proto3 string fields, which must hold valid UTF-8 (a
// peer refuses the whole message otherwise); short, so that a log line stays one line.
constexpr std::size_t kMaxNameBytes = 256;

bool check_name(Checker& check, const FieldPath& path, const std::string& name) {
  if (name.size() > kMaxNameBytes)
    return check.fail(path,
                      fmt::format("is {} bytes long, more than {}", name.size(), kMaxNameBytes));
  if (!google::protobuf::internal::IsStructurallyValidUTF8(name.data(),
                                                           static_cast<int>(name.size())))
    return check.fail(path, "is not valid UTF-8");
  return true;
}

}  // namespace scene::detail
