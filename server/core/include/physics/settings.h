#pragma once
// Every tunable of the world in one struct with inline defaults. The defaults are
// the ones the server uses; docs/ACCURACY.md says how each was chosen.
#include <cstdint>

#include "physics/vec2.h"

namespace phys {

// How a body's velocity and position advance over one step under constant
// acceleration a (input plus gravity) and friction rate k.
enum class Integrator : std::uint8_t {
  // x += v*dt, then v += a*dt (position uses the old velocity). First order.
  ExplicitEuler,
  // The classic recipe's integration: v = friction(v); v += a*dt; x += v*dt. First order,
  // symplectic. Friction uses the exact decay factor exp(-k*dt), never the lerp.
  SemiImplicitEuler,
  // The closed-form solution of dv/dt = a - k*v over the step (a held constant):
  // exact for free flight, so a parabola is followed to rounding. The default.
  Exact,
};

const char* to_string(Integrator integrator);

struct WorldSettings {
  Vec2 gravity{0.0, -9.81};
  Integrator integrator = Integrator::Exact;
  // Each step(dt) runs this many sub-steps of dt/substeps.
  int substeps = 1;
  // After resolving a penetration bodies are left this far apart (the recipe's
  // "tiny amount"), so that resting bodies do not touch on the other axis.
  double slop = 1.0e-5;
  // Gauss-Seidel passes over the contacts of each collide phase.
  int position_iterations = 4;
  // Passes over the contacts in the restitution phase.
  int velocity_iterations = 8;
  // Start each contact's impulse from the last step's (Box2D's warm starting), so
  // resting contacts converge over steps, not within one.
  bool warm_starting = true;
  // Swept (time-of-impact) motion against static bodies, so nothing tunnels.
  bool continuous = true;
  // Shock propagation: with gravity, a body resting on support is immovable for
  // the bodies above it. Makes stacks exact in one pass (docs/ACCURACY.md).
  bool shock_propagation = true;
  // With gravity, what a resting body's contacts held up in one sub-step is
  // applied as a force in the next, so resting bodies do not sink into their
  // supports and get pushed back out every step (docs/PHYSICS.md, "Resting contact").
  bool hold_resting_support = true;
  // A contact whose closing speed is below this keeps no bounce (resting contact).
  // 0 means "two steps of gravity": 2*|g|*dt.
  double rest_speed = 0.0;
  // Speeds and accelerations are clamped to these (the world stays finite).
  double max_speed = 1000.0;
  double max_acceleration = 1.0e5;
  // Bodies whose speed stays below sleep_speed for sleep_time seconds sleep and
  // cost nothing until something hits them.
  bool sleeping = true;
  double sleep_speed = 0.05;
  double sleep_time = 0.5;
  // Optional bounds: bodies may not be created outside; a dynamic body that leaves
  // them is clamped back in and counted.
  bool has_bounds = false;
  Aabb bounds{};
  // The largest radius or half extent a body may have, and most bodies at once.
  double max_body_size = 1.0e5;
  std::uint32_t max_bodies = 1u << 20;
  // Without contact friction, the velocity solver's iterations run two contacts at
  // a time in SIMD lanes where the build has them (SSE2: every x86-64 build), with
  // results equal bit for bit to the one-contact-at-a-time pass that false forces
  // (and that builds without SSE2 always run). A setting for tests and benchmarks.
  bool simd_contact_lanes = true;
  // Position passes after the second update each pair with a circle from the two
  // bodies' moves along the normal the second pass found (no square root, division
  // or shape test per pair) instead of running the narrowphase again. Off by
  // default: it saved 1 to 8% of a step on the rains and left their largest
  // overlap up to 2.6 times deeper (docs/ACCURACY.md, "Relaxed position passes").
  bool relaxed_position_passes = false;
  // Time each phase of the step into StepProfile (costs two clock reads a phase).
  bool profile = false;
};

// The largest gravity on either axis, in m/s^2 (a hundred thousand g): beyond it a
// step's arithmetic can overflow to infinity within a few steps.
inline constexpr double kMaxGravity = 1.0e6;

// Why a WorldSettings was refused.
enum class SettingsError : std::uint8_t {
  None,
  BadGravity,     // not finite, or beyond kMaxGravity on an axis
  BadSubsteps,    // < 1 or > 64
  BadSlop,        // not finite, < 0 or > 0.1
  BadIterations,  // < 1 or > 64
  BadSpeedLimit,  // not finite, or <= 0
  BadSleep,       // not finite, or < 0
  BadBounds,      // not finite, or min >= max
};

const char* describe(SettingsError error);
SettingsError check_settings(const WorldSettings& settings);

}  // namespace phys
