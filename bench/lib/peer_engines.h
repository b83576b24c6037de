#pragma once
// Factories of the engine adapters; each optional one is defined only when it is built in.
#include <memory>

#include "engine.h"

namespace bench {

std::unique_ptr<Engine> make_ours_engine(const SceneSpec& scene, const EngineOptions& options);
std::unique_ptr<Engine> make_baseline_engine(const SceneSpec& scene, const EngineOptions& options);
std::unique_ptr<Engine> make_box2d_engine(const SceneSpec& scene, const EngineOptions& options);
std::unique_ptr<Engine> make_chipmunk_engine(const SceneSpec& scene, const EngineOptions& options);

}  // namespace bench
