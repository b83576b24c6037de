#pragma once
// The named scenes of the report (docs/ACCURACY.md) and the microbenchmark's pile,
// built as engine-independent SceneSpecs. Every random choice comes from a fixed seed, so a
// scene is the same on every run and for every engine.
#include <cstdint>
#include <string>
#include <vector>

#include "physics/vec2.h"
#include "scene_spec.h"

namespace bench {

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

// The 16,000-circle pile as tests/stability/pile_test.cpp builds it: `count` circles of radius
// 0.5 rained into a container 100 m wide with walls 500 m high, 80 to a row 1.2 m
// apart from 1 m up, each nudged by up to 0.1 m and thrown sideways at up to 1 m/s
// (so that they tumble into a pile rather than land as columns), by the tests' own
// generator. Every body, walls included, has contact friction `mu`.
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

// splitmix64: a tiny generator whose output is fixed by the seed on every platform.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  double uniform(double lo, double hi);  // [lo, hi)

 private:
  std::uint64_t state_;
};

}  // namespace bench
