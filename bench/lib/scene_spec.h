#pragma once
// The bench runs the scenes of the scene library (testing/scenes, physics_scenes) and
// names its types as its own.
#include "scenes/scene_spec.h"

namespace bench {

using scenes::BodySpec;
using scenes::dynamic_count;
using scenes::SceneSpec;
using scenes::to_body_def;

}  // namespace bench
