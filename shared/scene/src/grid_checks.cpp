// Grids: rows of a repeated body, with taper and stagger.
#include "grid_checks.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>

#include "body_checks.h"

namespace scene::detail {

namespace proto = physics::scene;

namespace {

// How many bodies a grid makes, given counts already known to be in range.
std::int64_t grid_body_count(const proto::Grid& grid) {
  std::int64_t total = 0;
  for (std::int64_t row = 0; row < grid.count_y(); ++row) {
    const std::int64_t in_row = grid.count_x() - row * grid.taper();
    if (in_row <= 0) break;
    total += in_row;
  }
  return total;
}

}  // namespace

bool check_grid(Checker& check, const proto::Grid& grid, const FieldPath& path, SceneDef* def) {
  const phys::WorldSettings& settings = def->world;
  if (!grid.has_body()) return check.fail(path.child("body"), "missing: the body the grid repeats");
  phys::BodyDef body;
  if (!check_body(check, grid.body(), path.child("body"), settings, true, &body)) return false;
  if (!check.coordinate(path.child("origin"), grid.origin()) ||
      !check.finite(path.child("spacing"), grid.spacing()))
    return false;
  // Counts are checked one by one before any product is formed, so the total
  // below cannot overflow (at most 2^40) and is known before anything is made.
  if (!check.in_range(path.child("count_x"), grid.count_x(), 1, kMaxSceneBodies) ||
      !check.in_range(path.child("count_y"), grid.count_y(), 1, kMaxSceneBodies) ||
      !check.in_range(path.child("taper"), grid.taper(), 0, grid.count_x()))
    return false;
  const std::int64_t count = grid_body_count(grid);
  const auto already = static_cast<std::int64_t>(def->bodies.size());
  if (count > kMaxSceneBodies - already)
    return check.fail(path, fmt::format("makes {} bodies, and with the {} before it the scene "
                                        "would exceed its limit of {} bodies",
                                        count, already, kMaxSceneBodies));
  def->bodies.reserve(def->bodies.size() + static_cast<std::size_t>(count));
  const phys::Vec2 origin = to_vec(grid.origin());
  const phys::Vec2 spacing = to_vec(grid.spacing());
  for (std::int64_t row = 0; row < grid.count_y(); ++row) {
    const std::int64_t in_row = grid.count_x() - row * grid.taper();
    if (in_row <= 0) break;
    double shift = static_cast<double>(row * grid.taper()) * spacing.x * 0.5;
    if (grid.stagger() && row % 2 == 1) shift += spacing.x * 0.5;
    for (std::int64_t column = 0; column < in_row; ++column) {
      body.position = {origin.x + static_cast<double>(column) * spacing.x + shift,
                       origin.y + static_cast<double>(row) * spacing.y};
      // Formatted only on failure: a grid may place a million bodies.
      auto what = [&] { return fmt::format("body (row {}, column {})", row, column); };
      if (!is_finite(body.position) || std::fabs(body.position.x) > kMaxCoordinate ||
          std::fabs(body.position.y) > kMaxCoordinate)
        return check.fail(
            path, fmt::format("{} at ({}, {}) is beyond the largest |coordinate| {}", what(),
                              body.position.x, body.position.y, kMaxCoordinate));
      if (!inside_bounds(settings, body)) return check_inside(check, path, settings, body, what());
      def->bodies.push_back(body);
    }
  }
  return true;
}

}  // namespace scene::detail
