#include "sweep.h"

#include <algorithm>
#include <cmath>

#include "physics/formulas.h"

namespace phys {

namespace {
double component(const Vec2& v, int axis) { return axis == 0 ? v.x : v.y; }
}  // namespace

std::optional<Interval> overlap_interval(const Body& mover, const Body& obstacle, int axis,
                                         double side_tolerance) {
  const int other = 1 - axis;
  const double m_c = component(mover.position, other);
  const double o_c = component(obstacle.position, other);
  const double o_a = component(obstacle.position, axis);
  const double m_half_a = component(mover.half, axis);
  const double o_half_a = component(obstacle.half, axis);

  // How far the shapes reach toward each other along `axis`, given the offset on
  // the other axis: a flat face reaches its half size; a circle, the chord.
  if (mover.shape == Shape::Box && obstacle.shape == Shape::Box) {
    const double across =
        std::min(m_c + component(mover.half, other), o_c + component(obstacle.half, other)) -
        std::max(m_c - component(mover.half, other), o_c - component(obstacle.half, other));
    if (across <= side_tolerance) return std::nullopt;
    return Interval{o_a - o_half_a - m_half_a, o_a + o_half_a + m_half_a};
  }
  if (mover.shape == Shape::Circle && obstacle.shape == Shape::Circle) {
    const double reach = mover.radius + obstacle.radius;
    const double offset = std::fabs(m_c - o_c);
    if (offset >= reach) return std::nullopt;
    const double chord = std::sqrt(reach * reach - offset * offset);
    return Interval{o_a - chord, o_a + chord};
  }
  // One circle and one box: the circle's distance to the box's span on the other axis.
  const bool mover_is_circle = mover.shape == Shape::Circle;
  const Body& circle = mover_is_circle ? mover : obstacle;
  const Body& box = mover_is_circle ? obstacle : mover;
  const double circle_c = component(circle.position, other);
  const double box_c = component(box.position, other);
  const double box_half = component(box.half, other);
  const double offset = std::max(0.0, std::fabs(circle_c - box_c) - box_half);
  if (offset >= circle.radius) return std::nullopt;
  const double chord = std::sqrt(circle.radius * circle.radius - offset * offset);
  const double reach = (mover_is_circle ? o_half_a : m_half_a) + chord;
  return Interval{o_a - reach, o_a + reach};
}

double AxisPath::position(double t) const {
  if (t >= h) return x1;
  return position_at(integrator, x0, v0, a, k, h, t);
}

double AxisPath::velocity(double t) const {
  if (integrator != Integrator::Exact) return v1;  // constant within an Euler step
  return integrate_axis(Integrator::Exact, 0.0, v0, a, k, t).velocity;
}

std::optional<double> AxisPath::reaches(double level) const {
  const bool from_below = x0 < level;
  const auto past = [&](double x) { return from_below ? x >= level : x <= level; };

  // Split the step at the turning point, if the path has one: each part is monotonic.
  double turn = h;
  if (integrator == Integrator::Exact && a != 0.0) {
    if (k == 0.0) {
      turn = -v0 / a;
    } else {
      const double ratio = a / (a - k * v0);  // e^(-k t) at the turning point
      turn = (ratio > 0.0 && ratio < 1.0) ? -det::log(ratio) / k : h;
    }
    if (!(turn > 0.0 && turn < h)) turn = h;
  }
  double lo = 0.0;
  double hi = turn;
  if (!past(position(hi))) {
    if (turn >= h || !past(x1)) return std::nullopt;
    lo = turn;
    hi = h;
  }
  // Bisection keeps `hi` on the far side of the level: at hi the bodies touch or
  // overlap by no more than rounding.
  for (int i = 0; i < 64; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    if (past(position(mid))) {
      hi = mid;
    } else {
      lo = mid;
    }
  }
  return hi;
}

}  // namespace phys
