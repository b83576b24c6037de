#pragma once
// Factories of the peer adapters; each is defined only when its library is built in.
#include <memory>

#include "engine.h"

namespace bench {

std::unique_ptr<Engine> make_ours_engine(const SceneSpec& scene, const EngineOptions& options);
std::unique_ptr<Engine> make_box2d_engine(const SceneSpec& scene, const EngineOptions& options);
std::unique_ptr<Engine> make_chipmunk_engine(const SceneSpec& scene, const EngineOptions& options);

}  // namespace bench
