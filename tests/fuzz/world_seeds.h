#pragma once
// The seeds of world_bytes_fuzz: the bytes of a few small worlds, each stepped so
// that every part of the state has something in it (sleeping bodies, kinematic
// bodies, sensor overlaps, filters, names, contacts in touch, warm starts).
// make_fuzz_seeds writes them to corpus/world_bytes/.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "physics/world.h"

namespace fuzz_seeds {

inline phys::BodyDef body(phys::Shape shape, phys::Motion motion, phys::Vec2 at, phys::Vec2 half) {
  phys::BodyDef def;
  def.shape = shape;
  def.motion = motion;
  def.position = at;
  def.half_extents = half;
  def.radius = half.x;
  return def;
}

// A room: a floor, a wall, a kinematic sweeper pinning a circle against the wall,
// a named box inside a sensor, and a filtered box that falls through a ledge.
inline phys::World room() {
  using phys::Motion;
  using phys::Shape;
  phys::World world;
  world.set_contact_events(true);
  world.add_body(body(Shape::Box, Motion::Static, {0.0, -0.5}, {10.0, 0.5}));
  world.add_body(body(Shape::Box, Motion::Static, {4.0, 1.0}, {0.25, 1.0}));
  phys::BodyDef sweeper = body(Shape::Box, Motion::Kinematic, {1.0, 1.0}, {0.25, 1.0});
  sweeper.velocity = {2.0, 0.0};
  world.add_body(sweeper);
  world.add_body(body(Shape::Circle, Motion::Dynamic, {2.5, 0.3}, {0.3, 0.3}));
  phys::BodyDef sensor = body(Shape::Box, Motion::Static, {-4.0, 1.0}, {1.0, 1.0});
  sensor.is_sensor = true;
  sensor.name = "goal";
  world.add_body(sensor);
  phys::BodyDef ball = body(Shape::Box, Motion::Dynamic, {-4.0, 0.25}, {0.25, 0.25});
  ball.name = "ball";
  ball.contact_friction = 0.5;
  world.add_body(ball);
  phys::BodyDef ledge = body(Shape::Box, Motion::Static, {-1.0, 2.0}, {0.5, 0.1});
  ledge.filter.mask_bits = ~0x2u;
  world.add_body(ledge);
  phys::BodyDef ghost = body(Shape::Box, Motion::Dynamic, {-1.0, 3.0}, {0.2, 0.2});
  ghost.filter.category_bits = 0x2;
  world.add_body(ghost);
  for (int i = 0; i < 40; ++i) world.step(1.0 / 60.0);
  return world;
}

// A pile of boxes and circles, left long enough for some to fall asleep.
inline phys::World pile() {
  using phys::Motion;
  using phys::Shape;
  phys::WorldSettings settings;
  settings.substeps = 2;
  phys::World world(settings);
  world.add_body(body(Shape::Box, Motion::Static, {0.0, -0.5}, {6.0, 0.5}));
  for (int i = 0; i < 24; ++i) {
    const Shape shape = i % 2 == 0 ? Shape::Box : Shape::Circle;
    world.add_body(
        body(shape, Motion::Dynamic, {-3.0 + 0.55 * (i % 12), 0.3 + 0.7 * (i / 12)}, {0.25, 0.25}));
  }
  for (int i = 0; i < 150; ++i) world.step(1.0 / 60.0);
  return world;
}

// Each seed's file name and bytes.
inline std::vector<std::pair<std::string, std::vector<std::uint8_t>>> world_seeds() {
  return {{"empty", phys::World().to_bytes()},
          {"room", room().to_bytes()},
          {"pile", pile().to_bytes()}};
}

}  // namespace fuzz_seeds
