#include "test_scene.h"

namespace server_test {

scene::SceneDef free_space_scene() {
  scene::SceneDef scene;
  scene.name = "free space";
  scene.world.gravity = {0.0, 0.0};
  scene.tick_rate = 60.0;
  scene.steps_per_frame = 6;
  scene.max_acceleration = 50.0;
  scene.spawn_points = {{0.0, 0.0}, {10.0, 0.0}, {20.0, 0.0}};
  scene.player.shape = phys::Shape::Circle;
  scene.player.motion = phys::Motion::Dynamic;
  scene.player.radius = 0.5;
  scene.player.mass = 1.0;
  return scene;
}

scene::SceneDef scene_with_unowned_box() {
  scene::SceneDef scene = free_space_scene();
  phys::BodyDef box;
  box.shape = phys::Shape::Box;
  box.motion = phys::Motion::Dynamic;
  box.position = {-10.0, 0.0};
  box.half_extents = {0.5, 0.5};
  scene.bodies.push_back(box);
  return scene;
}

}  // namespace server_test
