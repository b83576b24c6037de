#include "text_draw.h"

#include <stb/stb_easy_font.h>

#include <vector>

namespace viewer {

// stb_easy_font indexes a table by character: only printable ASCII may reach it.
std::string printable(const std::string& text) {
  std::string out = text;
  for (char& c : out)
    if (c < 32 || c > 126) c = '?';
  return out;
}

float text_width(const std::string& text, float scale) {
  const std::string shown = printable(text);
  return static_cast<float>(stb_easy_font_width(const_cast<char*>(shown.c_str()))) * scale;
}

void draw_text(SDL_Renderer* renderer, float x, float y, float scale, const std::string& text,
               Rgb colour) {
  const std::string shown = printable(text);
  // stb_easy_font emits axis-aligned quads: 4 vertices of 16 bytes (x, y, z, colour).
  alignas(16) static char buffer[64 * 1024];
  const int quads = stb_easy_font_print(0.0f, 0.0f, const_cast<char*>(shown.c_str()), nullptr,
                                        buffer, sizeof(buffer));
  std::vector<SDL_FRect> rects;
  rects.reserve(static_cast<std::size_t>(quads));
  for (int q = 0; q < quads; ++q) {
    const float* v = reinterpret_cast<const float*>(buffer + q * 64);
    rects.push_back(
        {x + v[0] * scale, y + v[1] * scale, (v[8] - v[0]) * scale, (v[9] - v[1]) * scale});
  }
  SDL_SetRenderDrawBlendMode(renderer, SDL_BLENDMODE_NONE);
  SDL_SetRenderDrawColor(renderer, colour.r, colour.g, colour.b, 255);
  SDL_RenderFillRectsF(renderer, rects.data(), static_cast<int>(rects.size()));
}

}  // namespace viewer
