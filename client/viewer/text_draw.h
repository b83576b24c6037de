#pragma once
// Text on an SDL renderer with stb_easy_font: the panel's lines and the bodies'
// labels. Only printable ASCII is drawn; any other byte shows as '?'.
#include <SDL.h>

#include <string>

#include "palette.h"

namespace viewer {

// stb_easy_font's line height, unscaled (pixels).
inline constexpr float kTextLine = 12.0f;

std::string printable(const std::string& text);
// Width in pixels of `text` drawn at `scale`.
float text_width(const std::string& text, float scale);
// Draws `text` with its top-left corner at (x, y), each font pixel `scale` wide.
void draw_text(SDL_Renderer* renderer, float x, float y, float scale, const std::string& text,
               Rgb colour);

}  // namespace viewer
