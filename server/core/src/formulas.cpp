#include "physics/formulas.h"

#include <algorithm>
#include <cmath>

namespace phys {

double friction_decay_factor(double rate, double dt) { return std::exp(-rate * dt); }

double apply_friction(double velocity, double rate, double dt) {
  return velocity * friction_decay_factor(rate, dt);
}

namespace {

// phi1(t) = (1 - e^(-k t)) / k and phi2(t) = (t - phi1(t)) / k: the weights of v0
// and a in the closed form of dv/dt = a - k v. Their direct formulas cancel badly
// for small k*t, so below 1e-3 the Taylor series is used (error ~ (k t)^4 / 120).
struct Phi {
  double decay;  // e^(-k t)
  double phi1;
  double phi2;
};

Phi phi(double k, double t) {
  if (k == 0.0) return {1.0, t, 0.5 * t * t};
  const double kt = k * t;
  if (kt < 1.0e-3) {
    return {std::exp(-kt), t * (1.0 - kt / 2.0 + kt * kt / 6.0 - kt * kt * kt / 24.0),
            t * t * (0.5 - kt / 6.0 + kt * kt / 24.0 - kt * kt * kt / 120.0)};
  }
  const double decay = std::exp(-kt);
  const double p1 = -std::expm1(-kt) / k;
  return {decay, p1, (t - p1) / k};
}

}  // namespace

AxisMotion integrate_axis(Integrator integrator, double x, double v, double a, double k,
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
      const Phi p = phi(k, dt);
      return {x + v * p.phi1 + a * p.phi2, v * p.decay + a * p.phi1};
    }
  }
  return {x, v};
}

double position_at(Integrator integrator, double x, double v, double a, double k, double dt,
                   double t) {
  if (integrator == Integrator::Exact) {
    const Phi p = phi(k, t);
    return x + v * p.phi1 + a * p.phi2;
  }
  // The Euler variants move in a straight line within the step.
  const AxisMotion end = integrate_axis(integrator, x, v, a, k, dt);
  return dt > 0.0 ? x + (end.position - x) * (t / dt) : x;
}

double axis_penetration(double c1, double h1, double c2, double h2) {
  return std::fabs(std::fabs(c2 - c1) - h1 - h2);
}

Contact collide_circles(Vec2 c1, double r1, Vec2 c2, double r2) {
  const Vec2 d = c2 - c1;
  const double distance = length(d);
  Contact contact;
  if (!(distance <= r1 + r2)) return contact;
  contact.colliding = true;
  contact.penetration = std::fabs(distance - r1 - r2);
  // Coincident centres have no direction; push the second one up, by convention.
  contact.normal = distance > 0.0 ? d * (1.0 / distance) : Vec2{0.0, 1.0};
  return contact;
}

Contact collide_circle_box(Vec2 center, double radius, const Aabb& box) {
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

double mix_contact_friction(double a, double b) { return std::sqrt(a * b); }

bool apply_restitution(Vec2& v1, double inv_mass1, Vec2& v2, double inv_mass2, Vec2 n,
                       double restitution, double rest_speed) {
  const double inv_sum = inv_mass1 + inv_mass2;
  if (inv_sum <= 0.0) return false;
  const double closing = dot(v2 - v1, n);  // < 0: approaching
  if (closing >= 0.0) return false;
  const double e = effective_restitution(-closing, restitution, rest_speed);
  const double impulse = -(1.0 + e) * closing / inv_sum;
  v1 -= n * (impulse * inv_mass1);
  v2 += n * (impulse * inv_mass2);
  return true;
}

}  // namespace phys
