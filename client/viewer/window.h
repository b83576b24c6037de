#pragma once
// The interactive window: draws a world source every frame, with pan, zoom and
// follow (docs/VIEWER.md, Keys); the source handles its own keys first.
#include <cstdint>
#include <optional>

#include "camera.h"
#include "client/playout_buffer.h"
#include "options.h"
#include "world_shapes.h"
#include "world_source.h"

namespace viewer {

// The camera the flags ask for: --scale and --center, or what fits the world.
Camera initial_camera(const ViewerOptions& options, const WorldShapes& shapes);
// Centres the camera on body `id` when the frame holds it.
void follow(Camera& camera, const client::PlayoutFrame& frame, std::optional<std::uint64_t> id);

// Runs until the user quits; SDL's video must be initialised. 0, or kExitFailure
// when no window could be opened. `clock` gives seconds on a steady clock.
int run_window(const ViewerOptions& options, WorldSource& source, double (*clock)());

}  // namespace viewer
