#include "catalog.h"

#include "scenes/scenes.h"

namespace bench {

std::vector<SceneEntry> scene_catalog(const Mode& mode) {
  const int stack_steps = mode.quick ? 1200 : 10000;
  const int pyramid_steps = mode.quick ? 300 : 10000;
  const int rain_steps = mode.quick ? 480 : 1800;
  std::vector<SceneEntry> catalog;
  catalog.push_back({"projectile", ObserverKind::Trajectory, false, false, false,
                     [](const Mode&) { return scenes::projectile_scene(0.0); }});
  catalog.push_back({"projectile-friction", ObserverKind::Trajectory, false, false, false,
                     [](const Mode&) { return scenes::projectile_scene(0.8); }});
  for (double dt_k : {0.5, 1.0, 2.0, 10.0, 100.0}) {
    const SceneSpec probe = scenes::friction_decay_scene(dt_k);
    catalog.push_back({probe.name, ObserverKind::FrictionDecay, false, false, false,
                       [dt_k](const Mode&) { return scenes::friction_decay_scene(dt_k); }});
  }
  catalog.push_back({"bounce-e1", ObserverKind::Bounce, false, false, false,
                     [](const Mode&) { return scenes::bounce_scene(1.0, 6300); }});
  catalog.push_back({"bounce-e0.5", ObserverKind::Bounce, false, false, false,
                     [](const Mode&) { return scenes::bounce_scene(0.5, 600); }});
  catalog.push_back(
      {"column-50", ObserverKind::Stack, false, false, false,
       [stack_steps](const Mode&) { return scenes::column_scene(50, false, stack_steps); }});
  catalog.push_back(
      {"column-mass-10", ObserverKind::Stack, false, false, false,
       [stack_steps](const Mode&) { return scenes::column_scene(10, true, stack_steps); }});
  catalog.push_back(
      {"pyramid-5050", ObserverKind::Stack, true, true, true,
       [pyramid_steps](const Mode&) { return scenes::pyramid_scene(100, pyramid_steps); }});
  catalog.push_back({"rain-" + std::to_string(mode.rain_count), ObserverKind::Pile, true, true,
                     true, [rain_steps](const Mode& m) {
                       // Falling: the first second; settled: the last second.
                       return scenes::rain_scene(m.rain_count, rain_steps, 60, 60);
                     }});
  // The 16,000-circle pile as the stability test rains it (thrown sideways), 30 s:
  // from up to 240 m the last circles land after about 7 s. The test's friction is
  // 0.5; other coefficients show how the cost depends on it (a frictionless pile
  // flows for seconds after the rain has landed, a rough one stops where it lands).
  for (double mu : mode.pile_friction) {
    catalog.push_back({scenes::pile_rain_scene_name(mode.rain_count, mu), ObserverKind::Pile, true,
                       true, true, [rain_steps, mu](const Mode& m) {
                         return scenes::pile_rain_scene(m.rain_count, mu, rain_steps, 60, 60);
                       }});
  }
  const int stage_steps = mode.quick ? 120 : 600;
  for (scenes::StageVariant variant :
       {scenes::StageVariant::All, scenes::StageVariant::NoGravity,
        scenes::StageVariant::NoFriction, scenes::StageVariant::NoRestitution,
        scenes::StageVariant::CirclesOnly, scenes::StageVariant::BoxesOnly}) {
    const SceneSpec probe = scenes::stages_scene(variant, 1);
    catalog.push_back(
        {probe.name, ObserverKind::Stages, true, false, false, [variant, stage_steps](const Mode&) {
           return scenes::stages_scene(variant, stage_steps);
         }});
  }
  return catalog;
}

}  // namespace bench
