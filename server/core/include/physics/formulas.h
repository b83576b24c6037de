#pragma once
// The lecture's formulas, one function each, so that tests check them against
// hand-computed values and the world uses exactly these.
#include "physics/settings.h"
#include "physics/vec2.h"

namespace phys {

// Linear interpolation: (1 - t) * v0 + t * v1.
constexpr double lerp(double v0, double v1, double t) { return (1.0 - t) * v0 + t * v1; }

// The lecture's friction, v = lerp(v, 0, dt*k), overshoots once dt*k > 1 and
// diverges past 2. It is the first-order step of dv/dt = -k*v, whose exact
// solution over dt is v*exp(-k*dt): the same meaning (decay toward zero at rate k),
// stable for every dt*k >= 0, never changing sign and never growing.
double friction_decay_factor(double rate, double dt);
double apply_friction(double velocity, double rate, double dt);

// One axis of a body over one step: velocity v, position x, constant acceleration a
// (input plus gravity), friction rate k >= 0.
struct AxisMotion {
  double position;
  double velocity;
};
AxisMotion integrate_axis(Integrator integrator, double x, double v, double a, double k, double dt);
// Where the body is t seconds into the step (0 <= t <= dt), for time of impact.
double position_at(Integrator integrator, double x, double v, double a, double k, double dt,
                   double t);

// Box-box, the lecture's four separating conditions (a's bottom above b's top, a's
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
double axis_penetration(double c1, double h1, double c2, double h2);

// Circle-circle: colliding when distance <= r1 + r2; penetration |distance - r1 - r2|;
// normal points from the first centre toward the second.
struct Contact {
  bool colliding = false;
  double penetration = 0.0;
  Vec2 normal{};
};
Contact collide_circles(Vec2 c1, double r1, Vec2 c2, double r2);
// Circle against box, through the point of the box closest to the circle's centre.
// The normal points from the circle toward the box.
Contact collide_circle_box(Vec2 center, double radius, const Aabb& box);

// The restitution a contact gets: none when it closes slower than rest_speed (a
// resting contact, which then comes to rest exactly), else the material's. The one
// rule for swept bounces, contact impulses and apply_restitution alike.
constexpr double effective_restitution(double approach_speed, double restitution,
                                       double rest_speed) {
  return approach_speed < rest_speed ? 0.0 : restitution;
}

// Restitution of one contact along unit normal n (from body 1 toward body 2).
// inv_mass 0 is a static body. If the bodies approach, the normal component of the
// relative velocity is reflected and scaled by e (or zeroed below rest_speed), the
// impulse split by inverse mass. Returns false when nothing changed.
bool apply_restitution(Vec2& v1, double inv_mass1, Vec2& v2, double inv_mass2, Vec2 n,
                       double restitution, double rest_speed);

// Material mixing in one place, as Box2D does: restitution max(a, b), contact
// friction sqrt(a * b).
constexpr double mix_restitution(double a, double b) { return a > b ? a : b; }
double mix_contact_friction(double a, double b);

}  // namespace phys
