// Box2D 2.4.1 behind the bench's Engine interface, at its own defaults: 8 velocity
// and 3 position iterations, restitution threshold 1 m/s, sleeping as the caller
// asks. Boxes have fixed rotation (ours are axis-aligned). Box2D has no per-axis
// velocity decay; our friction rate k maps to its linear damping (one rate, the
// mean of both axes), which it applies as v /= 1 + k*dt. Contact (Coulomb)
// friction is the body's; Box2D mixes a pair's as the geometric mean, as ours does.
#include <box2d/box2d.h>

#include <memory>
#include <vector>

#include "peer_engines.h"

namespace bench {
namespace {

b2Vec2 to_b2(phys::Vec2 v) { return {static_cast<float>(v.x), static_cast<float>(v.y)}; }

class Box2DEngine final : public Engine {
 public:
  static constexpr int kVelocityIterations = 8;
  static constexpr int kPositionIterations = 3;

  Box2DEngine(const SceneSpec& scene, const EngineOptions& options)
      : world_(std::make_unique<b2World>(to_b2(scene.gravity))) {
    world_->SetAllowSleeping(options.sleeping);
    for (const BodySpec& spec : scene.bodies) add(spec, options.sleeping);
  }

  void step(double dt) override {
    for (const Driven& driven : driven_) {
      driven.body->ApplyForceToCenter(driven.force, true);
    }
    world_->Step(static_cast<float>(dt), kVelocityIterations, kPositionIterations);
  }

  void sample(std::vector<BodySample>& out) const override {
    out.clear();
    out.reserve(dynamic_.size());
    for (const b2Body* body : dynamic_) {
      const b2Vec2 p = body->GetPosition();
      const b2Vec2 v = body->GetLinearVelocity();
      out.push_back({{double{p.x}, double{p.y}}, {double{v.x}, double{v.y}}});
    }
  }

  std::size_t awake_count() const override {
    std::size_t awake = 0;
    for (const b2Body* body : dynamic_) {
      if (body->IsAwake()) ++awake;
    }
    return awake;
  }

  std::string iterations_label() const override { return "8v/3p"; }

 private:
  struct Driven {
    b2Body* body;
    b2Vec2 force;
  };

  void add(const BodySpec& spec, bool sleeping) {
    b2BodyDef def;
    def.type = spec.is_static ? b2_staticBody : b2_dynamicBody;
    def.position = to_b2(spec.position);
    def.linearVelocity = to_b2(spec.velocity);
    def.fixedRotation = true;
    def.allowSleep = sleeping;
    def.linearDamping = static_cast<float>((spec.friction.x + spec.friction.y) / 2.0);
    b2Body* body = world_->CreateBody(&def);

    b2FixtureDef fixture;
    fixture.friction = static_cast<float>(spec.contact_friction);
    fixture.restitution = static_cast<float>(spec.restitution);
    fixture.density = 1.0f;
    b2CircleShape circle;
    b2PolygonShape box;
    if (spec.shape == phys::Shape::Circle) {
      circle.m_radius = static_cast<float>(spec.radius);
      fixture.shape = &circle;
    } else {
      box.SetAsBox(static_cast<float>(spec.half_extents.x),
                   static_cast<float>(spec.half_extents.y));
      fixture.shape = &box;
    }
    body->CreateFixture(&fixture);
    if (spec.is_static) return;

    // b2Vec2's constructor leaves it uninitialised, so every field is set here.
    b2MassData mass;
    mass.mass = static_cast<float>(spec.mass);
    mass.center.SetZero();
    mass.I = 0.0f;
    body->SetMassData(&mass);
    dynamic_.push_back(body);
    if (spec.acceleration.x != 0.0 || spec.acceleration.y != 0.0) {
      driven_.push_back({body, to_b2(spec.acceleration * spec.mass)});
    }
  }

  std::unique_ptr<b2World> world_;
  std::vector<b2Body*> dynamic_;
  std::vector<Driven> driven_;
};

}  // namespace

std::unique_ptr<Engine> make_box2d_engine(const SceneSpec& scene, const EngineOptions& options) {
  return std::make_unique<Box2DEngine>(scene, options);
}

}  // namespace bench
