// Chipmunk 7 behind the bench's Engine interface, at its defaults: 10 iterations,
// its default spatial index (bounding-box tree) and collision slop (0.1). Boxes
// have fixed rotation (infinite moment). Sleeping: Chipmunk's is off unless a sleep
// time threshold is set; with sleeping on we set 0.5 s, as Box2D's and ours.
// Restitution: Chipmunk multiplies both shapes' elasticities, so static shapes get
// 1 and a contact keeps the dynamic body's value (ours and Box2D take the max).
// Our friction rate k becomes Chipmunk's own exponential damping, per body.
// Contact friction: Chipmunk multiplies both shapes' coefficients, where ours and
// Box2D take their geometric mean; each shape gets the square root of the body's,
// so that every pair's coefficient is the same in all three engines.
#include <chipmunk/chipmunk.h>
#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "peer_banners.h"
#include "peer_engines.h"

namespace bench {
namespace {

cpVect to_cp(phys::Vec2 v) { return cpv(v.x, v.y); }

// Chipmunk passes the space's per-step damping factor; each body multiplies in its
// own exp(-k*dt), Chipmunk's exponential decay at our rate k (stored as user data).
void damped_velocity(cpBody* body, cpVect gravity, cpFloat damping, cpFloat dt) {
  const double* rate = static_cast<const double*>(cpBodyGetUserData(body));
  cpBodyUpdateVelocity(body, gravity, damping * std::exp(-*rate * dt), dt);
}

class ChipmunkEngine final : public Engine {
 public:
  ChipmunkEngine(const SceneSpec& scene, const EngineOptions& options) : space_(cpSpaceNew()) {
    cpSpaceSetGravity(space_, to_cp(scene.gravity));
    if (options.sleeping) cpSpaceSetSleepTimeThreshold(space_, 0.5);
    rates_.reserve(scene.bodies.size());
    for (const BodySpec& spec : scene.bodies) add(spec);
  }

  ~ChipmunkEngine() override {
    for (cpShape* shape : shapes_) {
      cpSpaceRemoveShape(space_, shape);
      cpShapeFree(shape);
    }
    for (cpBody* body : dynamic_) {
      cpSpaceRemoveBody(space_, body);
      cpBodyFree(body);
    }
    cpSpaceFree(space_);
  }
  ChipmunkEngine(const ChipmunkEngine&) = delete;
  ChipmunkEngine& operator=(const ChipmunkEngine&) = delete;

  void step(double dt) override {
    for (const Driven& driven : driven_) cpBodySetForce(driven.body, driven.force);
    cpSpaceStep(space_, dt);
  }

  void sample(std::vector<BodySample>& out) const override {
    out.clear();
    out.reserve(dynamic_.size());
    for (const cpBody* body : dynamic_) {
      const cpVect p = cpBodyGetPosition(body);
      const cpVect v = cpBodyGetVelocity(body);
      out.push_back({{p.x, p.y}, {v.x, v.y}});
    }
  }

  std::size_t awake_count() const override {
    std::size_t awake = 0;
    for (const cpBody* body : dynamic_) {
      if (cpBodyIsSleeping(body) == 0) ++awake;
    }
    return awake;
  }

  std::string iterations_label() const override {
    return std::to_string(cpSpaceGetIterations(space_));
  }

 private:
  struct Driven {
    cpBody* body;
    cpVect force;
  };

  void add(const BodySpec& spec) {
    cpBody* body = nullptr;
    cpShape* shape = nullptr;
    if (spec.is_static) {
      body = cpSpaceGetStaticBody(space_);
      if (spec.shape == phys::Shape::Circle) {
        shape = cpCircleShapeNew(body, spec.radius, to_cp(spec.position));
      } else {
        const phys::Vec2 lo = spec.position - spec.half_extents;
        const phys::Vec2 hi = spec.position + spec.half_extents;
        shape = cpBoxShapeNew2(body, cpBBNew(lo.x, lo.y, hi.x, hi.y), 0.0);
      }
      cpShapeSetElasticity(shape, 1.0);
    } else {
      body = cpSpaceAddBody(space_, cpBodyNew(spec.mass, INFINITY));
      cpBodySetPosition(body, to_cp(spec.position));
      cpBodySetVelocity(body, to_cp(spec.velocity));
      rates_.push_back((spec.friction.x + spec.friction.y) / 2.0);
      if (rates_.back() > 0.0) {
        cpBodySetUserData(body, &rates_.back());
        cpBodySetVelocityUpdateFunc(body, damped_velocity);
      }
      dynamic_.push_back(body);
      if (spec.acceleration.x != 0.0 || spec.acceleration.y != 0.0) {
        driven_.push_back({body, to_cp(spec.acceleration * spec.mass)});
      }
      if (spec.shape == phys::Shape::Circle) {
        shape = cpCircleShapeNew(body, spec.radius, cpvzero);
      } else {
        shape = cpBoxShapeNew(body, 2.0 * spec.half_extents.x, 2.0 * spec.half_extents.y, 0.0);
      }
      cpShapeSetElasticity(shape, spec.restitution);
    }
    cpShapeSetFriction(shape, std::sqrt(spec.contact_friction));
    shapes_.push_back(cpSpaceAddShape(space_, shape));
  }

  cpSpace* space_;
  std::vector<cpBody*> dynamic_;
  std::vector<cpShape*> shapes_;
  std::vector<Driven> driven_;
  std::vector<double> rates_;  // reserved up front: bodies point into it
};

}  // namespace

std::unique_ptr<Engine> make_chipmunk_engine(const SceneSpec& scene, const EngineOptions& options) {
  return std::make_unique<ChipmunkEngine>(scene, options);
}

// The banner is printed once a process, by the first cpSpaceNew (a build of Chipmunk
// with its debug checks on, as Debian's is).
void absorb_chipmunk_banner() {
  std::fflush(stdout);
  const int saved = dup(STDOUT_FILENO);
  const int null = open("/dev/null", O_WRONLY);
  if (saved < 0 || null < 0) {
    if (saved >= 0) close(saved);
    if (null >= 0) close(null);
    return;
  }
  dup2(null, STDOUT_FILENO);
  cpSpaceFree(cpSpaceNew());
  std::fflush(stdout);
  dup2(saved, STDOUT_FILENO);
  close(saved);
  close(null);
}

}  // namespace bench
