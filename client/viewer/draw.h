#pragma once
// Drawing one frame on an SDL renderer (a window's, or a software renderer on a
// surface for screenshots): the background, the static bodies where the Welcome
// put them, every moving body where the playout buffer shows it (kinematic ones in
// their own colour), the sensors translucent over them, the own body's ring, the
// labels, then the panel.
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

// `own`: the body this viewer plays, ringed and labelled "(you)".
void draw_world(SDL_Renderer* renderer, const Camera& camera, const WorldShapes& shapes,
                const client::PlayoutFrame& frame, std::optional<std::uint64_t> followed,
                std::optional<std::uint64_t> own = std::nullopt);

// A player's body's label, empty for none: the own body's, and those of the moving
// bodies added since the Welcome (players who joined; the protocol does not say which
// of the Welcome's bodies are players'): the name, else "#id"; " (you)" on the own.
std::string body_label(const client::BodyShape& shape, const WorldShapes& shapes,
                       std::optional<std::uint64_t> own);

// Lines of text in the top-left corner on a dark panel (stb_easy_font, 2x).
void draw_panel(SDL_Renderer* renderer, const std::vector<std::string>& lines);

// The dynamic body under pixel `at`, if any (topmost: the highest id drawn last).
std::optional<std::uint64_t> body_at(const Camera& camera, const WorldShapes& shapes,
                                     const client::PlayoutFrame& frame, PixelPoint at);

}  // namespace viewer
