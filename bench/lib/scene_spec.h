#pragma once
// A scene described once, independently of the engine that runs it, so that ours
// and the peers start from exactly the same bodies.
#include <cstddef>
#include <string>
#include <vector>

#include "physics/body.h"
#include "physics/vec2.h"

namespace bench {

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

// The core's definition of the body a spec describes (what our engine adds).
phys::BodyDef to_body_def(const BodySpec& spec);

}  // namespace bench
