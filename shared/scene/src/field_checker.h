#pragma once
// The checker's machinery: the first fault found, with its field path and where the
// text wrote it, and the number checks (finite, positive, in range, a coordinate)
// that the world and body checks are made of.
#include <google/protobuf/text_format.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "field_path.h"
#include "physics/vec2.h"
#include "scene.pb.h"
#include "scene/scene.h"

namespace scene::detail {

// Records the first fault; every check returns false once one is recorded, so
// callers stop at the first `false`.
class Checker {
 public:
  Checker(std::string_view origin, const google::protobuf::TextFormat::ParseInfoTree& locations)
      : origin_(origin), locations_(locations) {}

  bool fail(const FieldPath& path, std::string message);
  SceneError take_error() { return std::move(*error_); }

  bool finite(const FieldPath& path, double value);
  bool positive(const FieldPath& path, double value);
  bool not_negative(const FieldPath& path, double value);
  bool at_most(const FieldPath& path, double value, double limit, std::string_view why);
  bool in_range(const FieldPath& path, double value, double low, double high);
  bool in_range(const FieldPath& path, std::int64_t value, std::int64_t low, std::int64_t high);
  bool finite(const FieldPath& path, const physics::scene::Vec2& value);
  // A position: finite and within kMaxCoordinate of the origin on both axes.
  bool coordinate(const FieldPath& path, const physics::scene::Vec2& value);

 private:
  std::string_view origin_;
  const google::protobuf::TextFormat::ParseInfoTree& locations_;
  std::optional<SceneError> error_;
};

// A name: short, and valid UTF-8 (it travels to clients in proto3 strings).
bool check_name(Checker& check, const FieldPath& path, const std::string& name);

inline phys::Vec2 to_vec(const physics::scene::Vec2& value) { return {value.x(), value.y()}; }

}  // namespace scene::detail
