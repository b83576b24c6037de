#include "test_scenes.h"

namespace itest {

scene::SceneDef free_flight_scene(bool with_gravity) {
  scene::SceneDef scene;
  scene.name = with_gravity ? "free-flight" : "free-flight-no-gravity";
  scene.world.gravity = with_gravity ? phys::Vec2{0.0, -9.81} : phys::Vec2{0.0, 0.0};
  scene.tick_rate = 60.0;
  scene.max_acceleration = 50.0;
  // Spawn points 1 km apart: no two players can meet within a test's few seconds.
  for (int i = 0; i < 8; ++i) scene.spawn_points.push_back({1000.0 * i, 100.0});
  scene.player.shape = phys::Shape::Circle;
  scene.player.motion = phys::Motion::Dynamic;
  scene.player.radius = 0.5;
  scene.player.mass = 1.0;
  scene.player.restitution = 0.0;
  scene.player.friction = {0.0, 0.0};
  return scene;
}

scene::SceneDef crowd_scene(std::size_t count) {
  scene::SceneDef scene = free_flight_scene(false);
  scene.name = "crowd";
  for (std::size_t i = 0; i < count; ++i) {
    phys::BodyDef body;
    body.shape = phys::Shape::Circle;
    body.radius = 0.25;
    body.position = {static_cast<double>(i % 100), -10.0 - static_cast<double>(i / 100)};
    scene.bodies.push_back(body);
  }
  return scene;
}

}  // namespace itest
