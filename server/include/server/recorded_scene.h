#pragma once
// A scene as a recording holds it (physics.recording.Scene: every setting and body
// explicit, bit for bit) and back, and the per-body hash recordings carry.
#include <cstdint>
#include <string>
#include <variant>

#include "physics/body.h"
#include "recording.pb.h"
#include "scene/scene.h"

namespace server {

physics::recording::Scene to_recorded(const scene::SceneDef& scene);
// The scene, or why it cannot be built (a setting or a body the core refuses, too
// many bodies); never throws.
std::variant<scene::SceneDef, std::string> from_recorded(const physics::recording::Scene& scene);

// 64-bit FNV-1a over one body's id, shape, motion, position, velocity, acceleration,
// radius and half extents, as exact bit patterns (docs/REPLAY.md, "Body hashes").
std::uint64_t body_hash(const phys::BodyState& body);

}  // namespace server
