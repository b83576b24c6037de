#pragma once
// Drawing one frame on an SDL renderer (a window's, or a software renderer on a
// surface for screenshots): the background, the static bodies where the Welcome
// put them, every dynamic body where the playout buffer shows it, then the panel.
#include <SDL.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "camera.h"
#include "client/playout_buffer.h"
#include "palette.h"
#include "world_shapes.h"

namespace viewer {

// Which colour a dynamic body gets.
Rgb dynamic_colour(const client::PlayoutBody& body, std::optional<std::uint64_t> followed);

void draw_world(SDL_Renderer* renderer, const Camera& camera, const WorldShapes& shapes,
                const client::PlayoutFrame& frame, std::optional<std::uint64_t> followed);

// Lines of text in the top-left corner on a dark panel (stb_easy_font, 2x).
void draw_panel(SDL_Renderer* renderer, const std::vector<std::string>& lines);

// The dynamic body under pixel `at`, if any (topmost: the highest id drawn last).
std::optional<std::uint64_t> body_at(const Camera& camera, const WorldShapes& shapes,
                                     const client::PlayoutFrame& frame, PixelPoint at);

}  // namespace viewer
