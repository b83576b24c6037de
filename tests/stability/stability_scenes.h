#pragma once
// The scenes of the hard cases, each built at an offset so that the far-from-origin
// test can build the very same scene 100 km away.
#include <cmath>
#include <cstdint>
#include <vector>

#include "physics_test_support.h"

namespace phys::testing {

// A static floor whose top is the line y = offset.y, 400 m wide.
inline BodyId add_floor(World& world, Vec2 offset) {
  return add_or_fail(world, box_def(offset + Vec2{0.0, -0.5}, {200.0, 0.5}, Motion::Static));
}

// A ball of radius 0.5 whose bottom is `height` over the floor.
inline BodyId add_dropped_ball(World& world, Vec2 offset, double height, double restitution) {
  add_floor(world, offset);
  BodyDef def = circle_def(offset + Vec2{0.0, height + 0.5}, 0.5);
  def.restitution = restitution;
  return add_or_fail(world, def);
}

// A column of unit boxes standing on the floor, exactly touching, bottom first.
// masses[i] is the mass of box i (bottom = 0).
inline std::vector<BodyId> add_column(World& world, Vec2 offset,
                                      const std::vector<double>& masses) {
  add_floor(world, offset);
  std::vector<BodyId> ids;
  for (std::size_t i = 0; i < masses.size(); ++i) {
    BodyDef def = box_def(offset + Vec2{0.0, 0.5 + static_cast<double>(i)}, {0.5, 0.5});
    def.mass = masses[i];
    ids.push_back(add_or_fail(world, def));
  }
  return ids;
}

// A pyramid of unit boxes with `base` boxes in the bottom row: row r holds
// base - r boxes, shifted half a box to the right of the row below (bricks), and
// neighbours in a row exactly touching. base = 100 gives 5050 boxes. Returns the
// ids row by row; the last id is the top box.
inline std::vector<BodyId> add_pyramid(World& world, Vec2 offset, int base) {
  add_floor(world, offset);
  std::vector<BodyId> ids;
  for (int row = 0; row < base; ++row) {
    for (int i = 0; i < base - row; ++i) {
      const Vec2 centre{-0.5 * base + 0.5 + 0.5 * row + i, 0.5 + row};
      ids.push_back(add_or_fail(world, box_def(offset + centre, {0.5, 0.5})));
    }
  }
  return ids;
}

// A floor of `tiles` static unit boxes side by side, exactly touching, tops at
// y = offset.y, the first one's left edge at offset.x - 2.
inline void add_tiled_floor(World& world, Vec2 offset, int tiles) {
  for (int i = 0; i < tiles; ++i) {
    const Vec2 centre{-1.5 + i, -0.5};
    add_or_fail(world, box_def(offset + centre, {0.5, 0.5}, Motion::Static));
  }
}

// Tunnelling: a static wall 0.1 m thick whose left face is x = offset.x - 0.05,
// and a bullet (circle r = 0.1 or box of half size 0.05) 5 m to its left at 200 m/s.
struct BulletScene {
  BodyId bullet;
  double wall_left;
  double bullet_half;  // radius or half width
};
inline BulletScene add_bullet_and_wall(World& world, Vec2 offset, Shape shape, Vec2 velocity,
                                       double restitution = 0.0) {
  add_or_fail(world, box_def(offset, {0.05, 4.0}, Motion::Static));
  const double half = shape == Shape::Circle ? 0.1 : 0.05;
  BodyDef def = shape == Shape::Circle ? circle_def(offset + Vec2{-5.0, 0.0}, half)
                                       : box_def(offset + Vec2{-5.0, 0.0}, {half, half});
  def.velocity = velocity;
  def.restitution = restitution;
  return {add_or_fail(world, def), offset.x - 0.05, half};
}

inline WorldSettings zero_gravity() {
  WorldSettings settings;
  settings.gravity = {0.0, 0.0};
  return settings;
}

}  // namespace phys::testing
