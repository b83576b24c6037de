#pragma once
// The deepest overlap between any two bodies of a sampled state, computed here with
// its own sweep along x (not the core's broadphase, so the measure does not share
// the code it measures). Shapes are taken as the scene defines them: a peer that
// keeps bodies apart by a skin (Box2D's polygon radius) shows no overlap.
#include <cstddef>
#include <span>

#include "engine.h"
#include "scene_spec.h"

namespace bench {

struct OverlapResult {
  double max_depth = 0.0;             // metres; 0 when nothing overlaps
  std::size_t overlapping_pairs = 0;  // pairs deeper than `report_above`
};

// `dynamic` holds the scene's dynamic bodies in scene order; static bodies are read
// from the scene. Static-static pairs are ignored.
OverlapResult max_overlap(const SceneSpec& scene, std::span<const BodySample> dynamic,
                          double report_above);

// Dynamic bodies outside the scene's container, or with a non-finite state.
std::size_t escaped_count(const SceneSpec& scene, std::span<const BodySample> dynamic);
std::size_t non_finite_count(std::span<const BodySample> dynamic);

}  // namespace bench
