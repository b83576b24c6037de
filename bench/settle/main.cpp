// physics-settle: how long a rained pile of circles takes to fall asleep.
//
//   physics-settle --width 20 --circles 300 --mu 0.5 --seconds 40
//
// Circles of radius 0.5 are rained into a container `width` metres wide, in rows
// 1.2 m apart from 1 m up, each with a random jitter of up to 0.1 m and a random
// sideways speed of up to 1 m/s: the scene library's rained_circles_scene, which the
// tests' rained piles use (tests/stability/resting_test.cpp). With --per-row N the
// rows hold N circles, centred, laid out as the 16,000-circle pile
// (tests/stability/pile_test.cpp: --width 100 --circles 16000 --per-row 80 is that
// pile, circle for circle). Prints the kinetic energy, the awake count and the worst
// overlap every 5 s, then the time from which every circle stayed asleep (or
// "never"), and the pairs overlapping by more than 5 mm and 1 cm at the end, with how
// many of them are side by side.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "finite_range.h"
#include "parse_flags.h"
#include "physics/world.h"
#include "scenes/scenes.h"

namespace {

using phys::BodyState;
using phys::Motion;
using phys::Vec2;

struct Options {
  double width = 20.0;
  int circles = 300;
  double mu = 0.5;
  int seconds = 40;
  int per_row = 0;  // 0: as many as fit, from the left wall
};

struct Overlaps {
  double worst = 0.0;  // of two circles, or of a circle and the container
  int over_5mm = 0;    // circle pairs
  int over_1cm = 0;
  int side_by_side_5mm = 0;  // of those, pairs whose normal is within 30 degrees of level
  int side_by_side_1cm = 0;
};

Overlaps overlaps(const phys::World& world, double half) {
  std::vector<BodyState> circles;
  world.for_each_body([&](const BodyState& b) {
    if (b.motion == Motion::Dynamic) circles.push_back(b);
  });
  std::sort(circles.begin(), circles.end(),
            [](const BodyState& a, const BodyState& b) { return a.position.x < b.position.x; });
  Overlaps o;
  for (std::size_t i = 0; i < circles.size(); ++i) {
    const Vec2 p = circles[i].position;
    o.worst = std::max({o.worst, 0.5 - p.y, p.x + 0.5 - half, -half - (p.x - 0.5)});
    for (std::size_t j = i + 1; j < circles.size() && circles[j].position.x - p.x < 1.0; ++j) {
      const Vec2 d = circles[j].position - p;
      const double depth = 1.0 - length(d);
      o.worst = std::max(o.worst, depth);
      const bool side_by_side = std::fabs(d.y) < 0.5;  // |sin| < 30 degrees at distance ~1
      if (depth > 0.005) {
        ++o.over_5mm;
        o.side_by_side_5mm += side_by_side ? 1 : 0;
      }
      if (depth > 0.01) {
        ++o.over_1cm;
        o.side_by_side_1cm += side_by_side ? 1 : 0;
      }
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"How long a rained pile of circles takes to fall asleep"};
  app.add_option("--width", o.width, "Inner width of the container (m)")
      ->check(bench::finite_range("width", 1.2, 1e4));
  app.add_option("--circles", o.circles, "Circles of radius 0.5")->check(CLI::Range(1, 1000000));
  app.add_option("--mu", o.mu, "Contact friction of every body")
      ->check(bench::finite_range("friction", 0.0, 10.0));
  app.add_option("--seconds", o.seconds, "Simulated seconds at 60 Hz")->check(CLI::Range(1, 3600));
  app.add_option("--per-row", o.per_row,
                 "Circles per row, centred, laid out as the 16,000-circle pile (0: as many as fit)")
      ->check(CLI::Range(0, 1000000));
  if (const auto exit_code = bench::parse_flags(app, argc, argv)) return *exit_code;
  // Rows 1.2 m apart that are wider than the container would start circles inside
  // or beyond its walls.
  if (o.per_row > 0 && 1.2 * o.per_row > o.width) {
    std::fprintf(stderr, "--per-row %d needs --width of at least %.1f m, not %g\n", o.per_row,
                 1.2 * o.per_row, o.width);
    return 2;
  }

  phys::World world;
  scenes::add_to_world(world, scenes::rained_circles_scene({o.width, o.circles, o.mu, o.per_row}));
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
      std::printf("t %5.1f s  KE %10.4g J  awake %zu  worst overlap %.4g m\n", step * kDt, energy,
                  world.awake_body_count(), overlaps(world, o.width / 2.0).worst);
    }
  }
  if (asleep_from > 0) {
    std::printf("asleep from %.2f s\n", asleep_from * kDt);
  } else {
    std::printf("asleep from never (within %d s)\n", o.seconds);
  }
  const Overlaps end = overlaps(world, o.width / 2.0);
  std::printf("worst overlap %.4g m\n", end.worst);
  std::printf("pairs over 5 mm %d (%d side by side), over 1 cm %d (%d side by side)\n",
              end.over_5mm, end.side_by_side_5mm, end.over_1cm, end.side_by_side_1cm);
  return 0;
}
