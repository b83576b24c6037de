#pragma once
// The generated scenes, as engine-independent SceneSpecs: the named scenes of the
// accuracy report (docs/ACCURACY.md), the microbenchmark's pile, and the rained piles
// of circles that the stability tests, physics-settle and the report share. Every
// random choice comes from a fixed seed, so a scene is the same on every run and for
// every engine; tests/unit/scene_library_test.cpp holds each to its bodies and to
// its state after a few steps.
#include <cstdint>
#include <string>
#include <vector>

#include "physics/vec2.h"
#include "scenes/random.h"
#include "scenes/scene_spec.h"

namespace scenes {

// One circle in free flight from the origin, v0 = (5, 10), input acceleration
// (3, 2) plus gravity, friction rate k on both axes; 2 s. Closed form exists.
SceneSpec projectile_scene(double friction_rate);
inline constexpr phys::Vec2 kProjectileVelocity{5.0, 10.0};
inline constexpr phys::Vec2 kProjectileAcceleration{3.0, 2.0};

// One circle, no gravity, v0 = (10, 0), friction rate k = dt_times_k / dt; 1 s.
SceneSpec friction_decay_scene(double dt_times_k);
inline constexpr double kFrictionInitialSpeed = 10.0;

// A ball of radius 0.5 dropped with its bottom `kBounceHeight` above a static
// floor whose top is y = 0.
SceneSpec bounce_scene(double restitution, int steps);
inline constexpr double kBounceHeight = 10.0;
inline constexpr double kBallRadius = 0.5;

// `count` unit boxes stacked on a floor (top y = 0). With growing_mass the masses
// grow geometrically from 1 at the bottom to 1000 at the top.
SceneSpec column_scene(int count, bool growing_mass, int steps);

// A pyramid of unit boxes, `base` on the bottom row, one fewer per row; neighbours
// on a row start 0.05 m apart, rows rest exactly on each other.
SceneSpec pyramid_scene(int base, int steps);

// `count` circles of radius 0.5 on a jittered lattice above an open container
// (floor and two walls), falling from rest.
SceneSpec rain_scene(int count, int steps, int first_window, int last_window);

// Circles of radius 0.5 rained into an open container: a floor whose top is y = 0 and
// two walls 500 m high, 1 m thick, every body with contact friction `mu`. The
// circles start in rows 1.2 m apart from 1 m up, each nudged sideways by up to 0.1 m
// and thrown sideways at up to 1 m/s (so that they tumble into a pile rather than
// land as columns), from one Rain generator: per circle the nudge, then the speed.
struct RainedCircles {
  double width = 20.0;  // the container's inside, x in [-width/2, width/2]
  int circles = 300;
  double mu = 0.5;
  // 0: rows of as many as fit (width / 1.2), from 0.6 m off the left wall, the
  // layout of the small and deep piles (tests/stability/resting_test.cpp);
  // N: rows of N, centred, the layout of the 16,000-circle pile. The two layouts
  // draw the same numbers but scale the nudge differently (0.1 * U(-1, 1) against
  // U(-0.1, 0.1)), which rounds differently; each is kept as the tests used it.
  int per_row = 0;
};
SceneSpec rained_circles_scene(const RainedCircles& rain);

// The 16,000-circle pile (tests/stability/pile_test.cpp): `count` circles, 80 to a
// row, in a container 100 m wide; 16,000 make a pile about 40 rows deep.
inline RainedCircles circle_pile(int count, double mu) { return {100.0, count, mu, 80}; }

// circle_pile as the report runs it: named pile-rain-<count>-mu<mu>, with its steps,
// timing windows, and the state read every 30 steps.
SceneSpec pile_rain_scene(int count, double mu, int steps, int first_window, int last_window);
std::string pile_rain_scene_name(int count, double mu);

// The microbenchmark's pile (docs/BENCHMARKS.md): `count` bodies, circles and boxes
// alternating, on a lattice in a container about twice as wide as sqrt(count) metres.
SceneSpec pile_scene(int count);

// "Model only what a scene needs": 4,000 bodies with random velocities in a closed
// box, gravity, friction 0.5/s, restitution 0.5, circles and boxes. A variant
// switches one thing off.
enum class StageVariant { All, NoGravity, NoFriction, NoRestitution, CirclesOnly, BoxesOnly };
SceneSpec stages_scene(StageVariant variant, int steps);

// Random boxes for the broadphase benchmark: sizes 0.2..1.2 m spread over a square
// that holds them at about `density` of its area.
std::vector<phys::Aabb> random_boxes(int count, double density, std::uint64_t seed);

}  // namespace scenes
