#include "server/spawn.h"

#include <algorithm>
#include <array>
#include <vector>

#include "physics/formulas.h"

namespace server {
namespace {

// Offsets of ring r, in a fixed order: the 8 compass directions.
std::array<phys::Vec2, 8> ring_offsets(int ring, phys::Vec2 step) {
  const double r = static_cast<double>(ring);
  const double dx = step.x * r;
  const double dy = step.y * r;
  return {
      {{0.0, dy}, {dx, 0.0}, {-dx, 0.0}, {dx, dy}, {-dx, dy}, {0.0, -dy}, {dx, -dy}, {-dx, -dy}}};
}

}  // namespace

std::optional<phys::Vec2> find_spawn_position(const scene::SceneDef& scene,
                                              const phys::World& world,
                                              std::optional<std::uint32_t> seat) {
  std::vector<phys::Aabb> occupied;
  occupied.reserve(world.body_count());
  world.for_each_body([&](const phys::BodyState& body) {
    occupied.push_back(phys::box_around(
        body.position, phys::half_size(body.shape, body.radius, body.half_extents)));
  });

  const phys::WorldSettings& settings = world.settings();
  const phys::Vec2 h =
      phys::half_size(scene.player.shape, scene.player.radius, scene.player.half_extents);
  // Touching counts as overlapping (as in the core's boxes_intersect): a body spawned
  // flush against another would be in contact from its first step.
  auto is_free = [&](phys::Vec2 at) {
    const phys::Aabb box = phys::box_around(at, h);
    if (settings.has_bounds && !phys::contains(settings.bounds, box)) return false;
    return std::none_of(occupied.begin(), occupied.end(),
                        [&](const phys::Aabb& other) { return phys::boxes_intersect(box, other); });
  };

  if (seat && !scene.spawn_points.empty()) {
    const phys::Vec2 own = scene.spawn_points[*seat % scene.spawn_points.size()];
    if (is_free(own)) return own;
  }
  for (const phys::Vec2& point : scene.spawn_points) {
    if (is_free(point)) return point;
  }
  const phys::Vec2 step{h.x * 2.5, h.y * 2.5};
  for (int ring = 1; ring <= kSpawnRings; ++ring) {
    for (const phys::Vec2& point : scene.spawn_points) {
      for (const phys::Vec2& offset : ring_offsets(ring, step)) {
        if (is_free(point + offset)) return point + offset;
      }
    }
  }
  return std::nullopt;
}

}  // namespace server
