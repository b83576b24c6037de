#include "scenes/scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "scenes/random.h"

namespace scenes {
namespace {

constexpr double kWallThickness = 1.0;

BodySpec static_box(phys::Vec2 center, phys::Vec2 half) {
  BodySpec body;
  body.shape = phys::Shape::Box;
  body.is_static = true;
  body.position = center;
  body.half_extents = half;
  return body;
}

BodySpec dynamic_circle(phys::Vec2 center, double radius) {
  BodySpec body;
  body.shape = phys::Shape::Circle;
  body.position = center;
  body.radius = radius;
  return body;
}

BodySpec dynamic_box(phys::Vec2 center, phys::Vec2 half) {
  BodySpec body;
  body.shape = phys::Shape::Box;
  body.position = center;
  body.half_extents = half;
  return body;
}

// A floor whose top is y = 0 spanning [left, right], and walls up to `height`.
void add_container(SceneSpec& scene, double left, double right, double height, bool lid) {
  const double t = kWallThickness;
  const double mid = (left + right) / 2.0;
  const double half_width = (right - left) / 2.0 + t;
  scene.bodies.push_back(static_box({mid, -t / 2.0}, {half_width, t / 2.0}));
  scene.bodies.push_back(static_box({left - t / 2.0, height / 2.0}, {t / 2.0, height / 2.0}));
  scene.bodies.push_back(static_box({right + t / 2.0, height / 2.0}, {t / 2.0, height / 2.0}));
  if (lid) scene.bodies.push_back(static_box({mid, height + t / 2.0}, {half_width, t / 2.0}));
  scene.container = {{left, 0.0}, {right, lid ? height : 1e300}};
}

void add_floor(SceneSpec& scene, double half_width) {
  scene.bodies.push_back(
      static_box({0.0, -kWallThickness / 2.0}, {half_width, kWallThickness / 2.0}));
}

// `count` bodies of size 1 on a lattice of pitch `pitch` inside [left, right],
// starting just above the floor, each nudged sideways by up to `jitter`.
void add_lattice(SceneSpec& scene, int count, double left, double right, double pitch,
                 double jitter, bool alternate_boxes, std::uint64_t seed) {
  SplitMix64 random(seed);
  const int per_row = std::max(1, static_cast<int>((right - left - pitch) / pitch));
  for (int i = 0; i < count; ++i) {
    const int row = i / per_row;
    const int column = i % per_row;
    const phys::Vec2 center{left + pitch * (column + 1) + random.uniform(-jitter, jitter),
                            pitch * (row + 0.5) + 0.5};
    if (alternate_boxes && i % 2 == 1) {
      scene.bodies.push_back(dynamic_box(center, {0.5, 0.5}));
    } else {
      scene.bodies.push_back(dynamic_circle(center, 0.5));
    }
  }
}

double lattice_top(int count, double left, double right, double pitch) {
  const int per_row = std::max(1, static_cast<int>((right - left - pitch) / pitch));
  const int rows = (count + per_row - 1) / per_row;
  return pitch * (rows + 0.5) + 1.0;
}

}  // namespace

SceneSpec projectile_scene(double friction_rate) {
  SceneSpec scene;
  scene.name = friction_rate > 0.0 ? "projectile-friction" : "projectile";
  scene.steps = 120;
  BodySpec ball = dynamic_circle({0.0, 0.0}, kBallRadius);
  ball.velocity = kProjectileVelocity;
  ball.acceleration = kProjectileAcceleration;
  ball.friction = {friction_rate, friction_rate};
  scene.bodies.push_back(ball);
  return scene;
}

SceneSpec friction_decay_scene(double dt_times_k) {
  SceneSpec scene;
  char name[48];
  std::snprintf(name, sizeof name, "friction-dtk-%g", dt_times_k);
  scene.name = name;
  scene.gravity = {0.0, 0.0};
  scene.steps = 60;
  const double rate = dt_times_k / scene.dt;
  BodySpec ball = dynamic_circle({0.0, 0.0}, kBallRadius);
  ball.velocity = {kFrictionInitialSpeed, 0.0};
  ball.friction = {rate, rate};
  scene.bodies.push_back(ball);
  return scene;
}

SceneSpec bounce_scene(double restitution, int steps) {
  SceneSpec scene;
  scene.name =
      restitution >= 1.0 ? "bounce-e1" : "bounce-e" + std::to_string(restitution).substr(0, 3);
  scene.steps = steps;
  add_floor(scene, 5.0);
  BodySpec ball = dynamic_circle({0.0, kBounceHeight + kBallRadius}, kBallRadius);
  ball.restitution = restitution;
  scene.bodies.push_back(ball);
  return scene;
}

SceneSpec column_scene(int count, bool growing_mass, int steps) {
  SceneSpec scene;
  scene.name = (growing_mass ? "column-mass-" : "column-") + std::to_string(count);
  scene.steps = steps;
  scene.sample_every = 10;
  add_floor(scene, 10.0);
  for (int i = 0; i < count; ++i) {
    BodySpec box = dynamic_box({0.0, 0.5 + i}, {0.5, 0.5});
    if (growing_mass && count > 1)
      box.mass = std::pow(1000.0, static_cast<double>(i) / (count - 1));
    scene.bodies.push_back(box);
  }
  return scene;
}

SceneSpec pyramid_scene(int base, int steps) {
  SceneSpec scene;
  scene.name = "pyramid-" + std::to_string(base * (base + 1) / 2);
  scene.steps = steps;
  scene.sample_every = 10;
  constexpr double pitch = 1.05;
  add_floor(scene, pitch * base);
  for (int row = 0; row < base; ++row) {
    const int in_row = base - row;
    const double left = -pitch * (in_row - 1) / 2.0;
    for (int i = 0; i < in_row; ++i) {
      scene.bodies.push_back(dynamic_box({left + pitch * i, 0.5 + row}, {0.5, 0.5}));
    }
  }
  return scene;
}

SceneSpec rain_scene(int count, int steps, int first_window, int last_window) {
  SceneSpec scene;
  scene.name = "rain-" + std::to_string(count);
  scene.steps = steps;
  scene.first_window = first_window;
  scene.last_window = last_window;
  scene.sample_every = 30;
  // Wide enough that the pile is about 40 rows deep for 16,000 circles.
  const double width = std::max(20.0, std::ceil(count / 40.0));
  const double pitch = 1.25;
  const double top = lattice_top(count, -width / 2.0, width / 2.0, pitch);
  add_container(scene, -width / 2.0, width / 2.0, top + 10.0, false);
  add_lattice(scene, count, -width / 2.0, width / 2.0, pitch, 0.1, false, 0x5EED0001ULL);
  return scene;
}

SceneSpec rained_circles_scene(const RainedCircles& rain) {
  SceneSpec scene;
  char name[80];
  std::snprintf(name, sizeof name, "rained-%d-w%g-mu%g%s", rain.circles, rain.width, rain.mu,
                rain.per_row > 0 ? "-centred" : "");
  scene.name = name;
  const double half = rain.width / 2.0;
  constexpr double wall_top = 500.0;
  add_container(scene, -half, half, wall_top, false);
  const int per_row =
      rain.per_row > 0 ? rain.per_row : std::max(1, static_cast<int>(rain.width / 1.2));
  const double first_x = rain.per_row > 0 ? 0.6 - 0.6 * per_row : -half + 0.6;
  Rain random;
  for (int n = 0; n < rain.circles; ++n) {
    const double nudge =
        rain.per_row > 0 ? random.uniform(-0.1, 0.1) : 0.1 * random.uniform(-1.0, 1.0);
    BodySpec circle =
        dynamic_circle({first_x + 1.2 * (n % per_row) + nudge, 1.0 + 1.2 * (n / per_row)}, 0.5);
    circle.velocity = {random.uniform(-1.0, 1.0), 0.0};
    scene.bodies.push_back(circle);
  }
  for (BodySpec& body : scene.bodies) body.contact_friction = rain.mu;
  return scene;
}

std::string pile_rain_scene_name(int count, double mu) {
  char name[64];
  std::snprintf(name, sizeof name, "pile-rain-%d-mu%g", count, mu);
  return name;
}

SceneSpec pile_rain_scene(int count, double mu, int steps, int first_window, int last_window) {
  SceneSpec scene = rained_circles_scene(circle_pile(count, mu));
  scene.name = pile_rain_scene_name(count, mu);
  scene.steps = steps;
  scene.first_window = first_window;
  scene.last_window = last_window;
  scene.sample_every = 30;
  return scene;
}

SceneSpec pile_scene(int count) {
  SceneSpec scene;
  scene.name = "pile-" + std::to_string(count);
  scene.steps = 1;
  const double width = std::max(10.0, std::ceil(2.0 * std::sqrt(static_cast<double>(count))));
  const double pitch = 1.2;
  const double top = lattice_top(count, -width / 2.0, width / 2.0, pitch);
  add_container(scene, -width / 2.0, width / 2.0, top + 10.0, false);
  add_lattice(scene, count, -width / 2.0, width / 2.0, pitch, 0.1, true, 0x5EED0002ULL);
  return scene;
}

SceneSpec stages_scene(StageVariant variant, int steps) {
  static constexpr const char* kNames[] = {"stages-all",          "stages-no-gravity",
                                           "stages-no-friction",  "stages-no-restitution",
                                           "stages-circles-only", "stages-boxes-only"};
  SceneSpec scene;
  scene.name = kNames[static_cast<int>(variant)];
  scene.steps = steps;
  scene.sample_every = 30;
  if (variant == StageVariant::NoGravity) scene.gravity = {0.0, 0.0};
  constexpr int count = 4000;
  constexpr double size = 120.0;
  add_container(scene, -size / 2.0, size / 2.0, size, true);
  SplitMix64 random(0x5EED0003ULL);
  constexpr double pitch = 1.5;
  const int per_row = static_cast<int>((size - pitch) / pitch);
  for (int i = 0; i < count; ++i) {
    const phys::Vec2 center{-size / 2.0 + pitch * (i % per_row + 1), pitch * (i / per_row + 1)};
    const bool box =
        variant == StageVariant::BoxesOnly || (variant != StageVariant::CirclesOnly && i % 2 == 1);
    BodySpec body = box ? dynamic_box(center, {0.5, 0.5}) : dynamic_circle(center, 0.5);
    body.velocity = {random.uniform(-5.0, 5.0), random.uniform(-5.0, 5.0)};
    if (variant != StageVariant::NoFriction) body.friction = {0.5, 0.5};
    if (variant != StageVariant::NoRestitution) body.restitution = 0.5;
    scene.bodies.push_back(body);
  }
  return scene;
}

std::vector<phys::Aabb> random_boxes(int count, double density, std::uint64_t seed) {
  SplitMix64 random(seed);
  // Mean size 0.7 m: mean area about 0.53 m^2.
  const double side = std::sqrt(count * 0.53 / density);
  std::vector<phys::Aabb> boxes;
  boxes.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const phys::Vec2 c{random.uniform(0.0, side), random.uniform(0.0, side)};
    const phys::Vec2 h{random.uniform(0.1, 0.6), random.uniform(0.1, 0.6)};
    boxes.push_back({c - h, c + h});
  }
  return boxes;
}

}  // namespace scenes
