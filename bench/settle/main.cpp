// physics-settle: how long a rained pile of circles takes to fall asleep.
//
//   physics-settle --width 20 --circles 300 --mu 0.5 --seconds 40
//
// Circles of radius 0.5 are rained into a container `width` metres wide, in rows
// 1.2 m apart from 1 m up, each with a random jitter of up to 0.1 m and a random
// sideways speed of up to 1 m/s (the generator and layout of the tests'
// rained piles, tests/stability/resting_test.cpp). Prints the kinetic energy and
// the awake count every 5 s, then the time from which every circle stayed asleep
// (or "never") and the worst overlap at the end.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <vector>

#include "physics/world.h"
#include "rain.h"

namespace {

using phys::BodyDef;
using phys::BodyState;
using phys::Motion;
using phys::Shape;
using phys::Vec2;
using phys::testing::Rain;

struct Options {
  double width = 20.0;
  int circles = 300;
  double mu = 0.5;
  int seconds = 40;
};

void build(phys::World& world, const Options& o) {
  const double half = o.width / 2.0;
  const auto fixed = [&](Vec2 centre, Vec2 half_extents) {
    BodyDef def;
    def.motion = Motion::Static;
    def.position = centre;
    def.half_extents = half_extents;
    def.contact_friction = o.mu;
    world.add_body(def);
  };
  fixed({0.0, -0.5}, {half + 1.0, 0.5});
  fixed({-half - 0.5, 250.0}, {0.5, 250.0});
  fixed({half + 0.5, 250.0}, {0.5, 250.0});
  const int per_row = std::max(1, static_cast<int>(o.width / 1.2));
  Rain rain;
  for (int n = 0; n < o.circles; ++n) {
    BodyDef def;
    def.shape = Shape::Circle;
    def.radius = 0.5;
    def.position = {-half + 0.6 + 1.2 * (n % per_row) + 0.1 * rain.uniform(-1.0, 1.0),
                    1.0 + 1.2 * (n / per_row)};
    def.velocity = {rain.uniform(-1.0, 1.0), 0.0};
    def.contact_friction = o.mu;
    world.add_body(def);
  }
}

// The deepest overlap of two circles or of a circle and the container.
double worst_overlap(const phys::World& world, double half) {
  std::vector<BodyState> circles;
  world.for_each_body([&](const BodyState& b) {
    if (b.motion == Motion::Dynamic) circles.push_back(b);
  });
  std::sort(circles.begin(), circles.end(),
            [](const BodyState& a, const BodyState& b) { return a.position.x < b.position.x; });
  double worst = 0.0;
  for (std::size_t i = 0; i < circles.size(); ++i) {
    const Vec2 p = circles[i].position;
    worst = std::max({worst, 0.5 - p.y, p.x + 0.5 - half, -half - (p.x - 0.5)});
    for (std::size_t j = i + 1; j < circles.size() && circles[j].position.x - p.x < 1.0; ++j) {
      worst = std::max(worst, 1.0 - length(circles[j].position - p));
    }
  }
  return worst;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"How long a rained pile of circles takes to fall asleep"};
  app.add_option("--width", o.width, "Inner width of the container (m)")
      ->check(CLI::Range(1.2, 1e4));
  app.add_option("--circles", o.circles, "Circles of radius 0.5")->check(CLI::Range(1, 1000000));
  app.add_option("--mu", o.mu, "Contact friction of every body")->check(CLI::Range(0.0, 10.0));
  app.add_option("--seconds", o.seconds, "Simulated seconds at 60 Hz")->check(CLI::Range(1, 3600));
  CLI11_PARSE(app, argc, argv);

  phys::World world;
  build(world, o);
  constexpr double kDt = 1.0 / 60.0;
  int asleep_from = -1;  // the step from which every circle stayed asleep
  for (int step = 1; step <= o.seconds * 60; ++step) {
    world.step(kDt);
    const bool all_asleep = world.awake_body_count() == 0;
    if (!all_asleep) asleep_from = -1;
    if (all_asleep && asleep_from < 0) asleep_from = step;
    if (step % 300 == 0) {
      double energy = 0.0;
      world.for_each_body([&](const BodyState& b) {
        if (b.motion == Motion::Dynamic) energy += 0.5 * b.mass * dot(b.velocity, b.velocity);
      });
      std::printf("t %5.1f s  KE %10.4g J  awake %zu\n", step * kDt, energy,
                  world.awake_body_count());
    }
  }
  if (asleep_from > 0) {
    std::printf("asleep from %.2f s\n", asleep_from * kDt);
  } else {
    std::printf("asleep from never (within %d s)\n", o.seconds);
  }
  std::printf("worst overlap %.4g m\n", worst_overlap(world, o.width / 2.0));
  return 0;
}
