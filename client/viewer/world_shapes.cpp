#include "world_shapes.h"

#include <fmt/format.h>

#include <algorithm>

namespace viewer {

void WorldShapes::reset(const std::vector<client::BodyShape>& bodies) {
  shapes_.clear();
  statics_ = 0;
  joined_ = 0;
  left_ = 0;
  joined_ids_.clear();
  for (const client::BodyShape& body : bodies) {
    if (shapes_.insert_or_assign(body.body_id, body).second && body.is_static) ++statics_;
  }
}

void WorldShapes::apply(const client::Snapshot& snapshot) {
  for (const client::BodyShape& body : snapshot.added) {
    if (!shapes_.insert_or_assign(body.body_id, body).second) continue;
    if (body.is_static) {
      ++statics_;
    } else {
      ++joined_;
      joined_ids_.insert(body.body_id);
    }
  }
  for (const std::uint64_t id : snapshot.removed) {
    const auto it = shapes_.find(id);
    if (it == shapes_.end()) continue;
    if (it->second.is_static) {
      --statics_;
    } else {
      ++left_;
    }
    joined_ids_.erase(id);
    shapes_.erase(it);
  }
}

const client::BodyShape* WorldShapes::find(std::uint64_t id) const {
  const auto it = shapes_.find(id);
  return it == shapes_.end() ? nullptr : &it->second;
}

std::vector<client::BodyShape> WorldShapes::list() const {
  std::vector<client::BodyShape> out;
  out.reserve(shapes_.size());
  for (const auto& [id, shape] : shapes_) out.push_back(shape);
  return out;
}

std::string WorldShapes::bodies_line(const client::PlayoutFrame& frame,
                                     std::optional<std::uint64_t> followed) const {
  const auto still = static_cast<std::size_t>(
      std::count_if(frame.bodies.begin(), frame.bodies.end(),
                    [](const client::PlayoutBody& body) { return body.still; }));
  std::string line =
      fmt::format("bodies: {} dynamic ({} still), {} static", frame.bodies.size(), still, statics_);
  if (followed) line += fmt::format("  following {}", *followed);
  return line;
}

}  // namespace viewer
