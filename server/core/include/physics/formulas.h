#pragma once
// The classic recipe's formulas (docs/PHYSICS.md), one function each, so that tests
// check them against hand-computed values and the world uses exactly these. The ones
// the step calls per body or per pair are defined here, inline: a call into another
// translation unit per pair (and a Contact returned through memory) cost more than the
// formula.
#include <algorithm>
#include <cmath>

#include "physics/det_math.h"
#include "physics/settings.h"
#include "physics/vec2.h"

namespace phys {

// Linear interpolation: (1 - t) * v0 + t * v1.
constexpr double lerp(double v0, double v1, double t) { return (1.0 - t) * v0 + t * v1; }

// The recipe's velocity decay, v = lerp(v, 0, dt*k), overshoots once dt*k > 1 and
// diverges past 2. It is the first-order step of dv/dt = -k*v, whose exact
// solution over dt is v*exp(-k*dt): the same meaning (decay toward zero at rate k),
// stable for every dt*k >= 0, never changing sign and never growing. exp, expm1 and
// log in the step are det::'s (physics/det_math.h), which round alike on every platform.
inline double friction_decay_factor(double rate, double dt) { return det::exp(-rate * dt); }
inline double apply_friction(double velocity, double rate, double dt) {
  return velocity * friction_decay_factor(rate, dt);
}

// One axis of a body over one step: velocity v, position x, constant acceleration a
// (input plus gravity), friction rate k >= 0.
struct AxisMotion {
  double position;
  double velocity;
};

namespace detail {
// phi1(t) = (1 - e^(-k t)) / k and phi2(t) = (t - phi1(t)) / k: the weights of v0
// and a in the closed form of dv/dt = a - k v. Their direct formulas cancel badly
// for small k*t, so below 1e-3 the Taylor series is used (error ~ (k t)^4 / 120).
struct Phi {
  double decay;  // e^(-k t)
  double phi1;
  double phi2;
};

inline Phi phi(double k, double t) {
  if (k == 0.0) return {1.0, t, 0.5 * t * t};
  const double kt = k * t;
  if (kt < 1.0e-3) {
    return {det::exp(-kt), t * (1.0 - kt / 2.0 + kt * kt / 6.0 - kt * kt * kt / 24.0),
            t * t * (0.5 - kt / 6.0 + kt * kt / 24.0 - kt * kt * kt / 120.0)};
  }
  const double decay = det::exp(-kt);
  const double p1 = -det::expm1(-kt) / k;
  return {decay, p1, (t - p1) / k};
}
}  // namespace detail

inline AxisMotion integrate_axis(Integrator integrator, double x, double v, double a, double k,
                                 double dt) {
  switch (integrator) {
    case Integrator::ExplicitEuler: {
      const double moved = x + v * dt;  // the old velocity moves the body
      return {moved, apply_friction(v, k, dt) + a * dt};
    }
    case Integrator::SemiImplicitEuler: {
      const double v1 = apply_friction(v, k, dt) + a * dt;
      return {x + v1 * dt, v1};
    }
    case Integrator::Exact: {
      // v(t) = v0 e^(-kt) + a phi1(t);  x(t) = x0 + v0 phi1(t) + a phi2(t).
      // With k = 0: v0 + a t and x0 + v0 t + a t^2 / 2.
      const detail::Phi p = detail::phi(k, dt);
      return {x + v * p.phi1 + a * p.phi2, v * p.decay + a * p.phi1};
    }
  }
  return {x, v};
}

// Where the body is t seconds into the step (0 <= t <= dt), for time of impact.
inline double position_at(Integrator integrator, double x, double v, double a, double k, double dt,
                          double t) {
  if (integrator == Integrator::Exact) {
    const detail::Phi p = detail::phi(k, t);
    return x + v * p.phi1 + a * p.phi2;
  }
  // The Euler variants move in a straight line within the step.
  const AxisMotion end = integrate_axis(integrator, x, v, a, k, dt);
  return dt > 0.0 ? x + (end.position - x) * (t / dt) : x;
}

// Box-box, the recipe's four separating conditions (a's bottom above b's top, a's
// top below b's bottom, a's left right of b's right, a's right left of b's left).
// If none holds they intersect: touching counts as intersecting.
constexpr bool box_bottom_above_top(const Aabb& a, const Aabb& b) { return a.min.y > b.max.y; }
constexpr bool box_top_below_bottom(const Aabb& a, const Aabb& b) { return a.max.y < b.min.y; }
constexpr bool box_left_right_of_right(const Aabb& a, const Aabb& b) { return a.min.x > b.max.x; }
constexpr bool box_right_left_of_left(const Aabb& a, const Aabb& b) { return a.max.x < b.min.x; }
constexpr bool boxes_intersect(const Aabb& a, const Aabb& b) {
  return !(box_bottom_above_top(a, b) || box_top_below_bottom(a, b) ||
           box_left_right_of_right(a, b) || box_right_left_of_left(a, b));
}
// |distance - size1/2 - size2/2| on one axis, for centres c1, c2 and half sizes h1, h2.
inline double axis_penetration(double c1, double h1, double c2, double h2) {
  return std::fabs(std::fabs(c2 - c1) - h1 - h2);
}

// Circle-circle: colliding when distance <= r1 + r2; penetration |distance - r1 - r2|;
// normal points from the first centre toward the second.
struct Contact {
  bool colliding = false;
  double penetration = 0.0;
  Vec2 normal{};
};
inline Contact collide_circles(Vec2 c1, double r1, Vec2 c2, double r2) {
  const Vec2 d = c2 - c1;
  const double reach = r1 + r2;
  const double squared = dot(d, d);
  Contact contact;
  // Surely apart, by far more than rounding: no square root. Every pair this lets
  // through is decided by the exact test below, so the answer is the same. (Not
  // for reaches whose square is subnormal, where rounding is no longer relative.)
  const double reach_squared = reach * reach;
  if (reach_squared > 1.0e-300 && squared > reach_squared * (1.0 + 1.0e-10)) return contact;
  const double distance = std::sqrt(squared);
  if (!(distance <= reach)) return contact;
  contact.colliding = true;
  contact.penetration = std::fabs(distance - r1 - r2);
  // Coincident centres have no direction; push the second one up, by convention.
  contact.normal = distance > 0.0 ? d * (1.0 / distance) : Vec2{0.0, 1.0};
  return contact;
}
// Circle against box, through the point of the box closest to the circle's centre.
// The normal points from the circle toward the box.
inline Contact collide_circle_box(Vec2 center, double radius, const Aabb& box) {
  const Vec2 closest{std::clamp(center.x, box.min.x, box.max.x),
                     std::clamp(center.y, box.min.y, box.max.y)};
  const Vec2 d = closest - center;
  const double distance = length(d);
  Contact contact;
  if (distance > 0.0) {
    if (!(distance <= radius)) return contact;
    contact.colliding = true;
    contact.penetration = radius - distance;
    contact.normal = d * (1.0 / distance);
    return contact;
  }
  // The centre is inside the box: leave through the nearest face.
  const double to_left = center.x - box.min.x;
  const double to_right = box.max.x - center.x;
  const double to_bottom = center.y - box.min.y;
  const double to_top = box.max.y - center.y;
  const double nearest = std::min(std::min(to_left, to_right), std::min(to_bottom, to_top));
  contact.colliding = true;
  contact.penetration = radius + nearest;
  // The normal points from the circle toward the box: opposite the way out.
  if (nearest == to_top) {
    contact.normal = {0.0, -1.0};
  } else if (nearest == to_bottom) {
    contact.normal = {0.0, 1.0};
  } else if (nearest == to_left) {
    contact.normal = {1.0, 0.0};
  } else {
    contact.normal = {-1.0, 0.0};
  }
  return contact;
}

// The restitution a contact gets: none when it closes slower than rest_speed (a
// resting contact, which then comes to rest exactly), else the material's. The one
// rule for swept bounces and contact impulses alike.
constexpr double effective_restitution(double approach_speed, double restitution,
                                       double rest_speed) {
  return approach_speed < rest_speed ? 0.0 : restitution;
}

// Material mixing in one place, as Box2D does: restitution max(a, b), contact
// friction sqrt(a * b).
constexpr double mix_restitution(double a, double b) { return a > b ? a : b; }
inline double mix_contact_friction(double a, double b) { return std::sqrt(a * b); }

}  // namespace phys
