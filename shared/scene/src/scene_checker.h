#pragma once
// The scene message -> SceneDef, checking every number on the way. The first
// fault found is returned, naming its field path and, from the parser's record of
// locations, the line and column where it was written.
#include <google/protobuf/text_format.h>

#include <string_view>

#include "scene.pb.h"
#include "scene/scene.h"

namespace scene::detail {

SceneResult check_scene(const physics::scene::Scene& message, std::string_view origin,
                        const google::protobuf::TextFormat::ParseInfoTree& locations);

}  // namespace scene::detail
