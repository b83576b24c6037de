#pragma once
// A scene described once, independently of the engine that runs it, so that our
// world and the benchmarks' peers (Box2D, Chipmunk) start from exactly the same
// bodies, in the same order.
#include <cstddef>
#include <string>
#include <vector>

#include "physics/body.h"
#include "physics/vec2.h"

namespace phys {
class World;
}

namespace scenes {

struct BodySpec {
  phys::Shape shape = phys::Shape::Box;
  bool is_static = false;
  phys::Vec2 position{};
  phys::Vec2 velocity{};
  phys::Vec2 acceleration{};  // held constant for the whole run
  double radius = 0.5;
  phys::Vec2 half_extents{0.5, 0.5};
  double mass = 1.0;
  double restitution = 0.0;
  phys::Vec2 friction{};  // velocity decay rate per axis, 1/s
  // Coulomb friction between touching bodies; a pair's coefficient is the
  // geometric mean of its two bodies' (ours and Box2D's rule).
  double contact_friction = 0.0;
};

struct SceneSpec {
  std::string name;
  phys::Vec2 gravity{0.0, -9.81};
  double dt = 1.0 / 60.0;
  int steps = 60;
  std::vector<BodySpec> bodies;
  // Timing windows: the first `first_window` steps (e.g. a rain while it falls) and
  // the last `last_window` steps (e.g. the settled pile). 0 leaves a window out.
  int first_window = 0;
  int last_window = 0;
  // The state is read every `sample_every` steps (and after the last one).
  int sample_every = 1;
  // Where the dynamic bodies must stay (rain: the container's inside).
  phys::Aabb container{{-1e300, -1e300}, {1e300, 1e300}};
};

std::size_t dynamic_count(const SceneSpec& scene);

// The core's definition of the body a spec describes.
phys::BodyDef to_body_def(const BodySpec& spec);

// Adds every body of the scene to `world`, in the scene's order, and returns their
// ids in that order. The world's gravity is the
// caller's (a scene's is in scene.gravity). A body the world refuses throws
// std::invalid_argument naming the scene, the body's index and the reason: a
// scene of this library that a world refuses is a bug of the library or of the
// world's settings, never an input to recover from.
std::vector<phys::BodyId> add_to_world(phys::World& world, const SceneSpec& scene);

}  // namespace scenes
