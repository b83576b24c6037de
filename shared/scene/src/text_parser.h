#pragma once
// Scene text -> the scene message, with the first syntax error (or unknown field)
// reported with its line and column, and the location of every field recorded so
// that later checks can point into the text too.
#include <google/protobuf/text_format.h>

#include <optional>
#include <string_view>

#include "scene.pb.h"
#include "scene/scene.h"

namespace scene::detail {

// Parses `text` into `*message` and records field locations into `*locations`.
// Returns the error when the text does not parse; `origin` names the file.
std::optional<SceneError> parse_text(std::string_view text, std::string_view origin,
                                     physics::scene::Scene* message,
                                     google::protobuf::TextFormat::ParseInfoTree* locations);

}  // namespace scene::detail
