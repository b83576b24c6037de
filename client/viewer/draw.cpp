#include "draw.h"

#include <stb/stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace viewer {
namespace {

SDL_Color sdl(Rgb c, std::uint8_t alpha = 255) { return SDL_Color{c.r, c.g, c.b, alpha}; }

void set_colour(SDL_Renderer* renderer, Rgb c, std::uint8_t alpha = 255) {
  SDL_SetRenderDrawColor(renderer, c.r, c.g, c.b, alpha);
}

float to_float(double value) {
  // Far off-screen coordinates are clamped, so that a huge zoom cannot overflow
  // the renderer's float or int arithmetic.
  return static_cast<float>(std::clamp(value, -1e6, 1e6));
}

void fill_box(SDL_Renderer* renderer, const Camera& camera, client::Vec2 centre, client::Vec2 half,
              Rgb colour) {
  const PixelPoint top_left = camera.to_pixel({centre.x - half.x, centre.y + half.y});
  const PixelPoint bottom_right = camera.to_pixel({centre.x + half.x, centre.y - half.y});
  const SDL_FRect rect{to_float(top_left.x), to_float(top_left.y),
                       to_float(bottom_right.x - top_left.x),
                       to_float(bottom_right.y - top_left.y)};
  set_colour(renderer, colour);
  SDL_RenderFillRectF(renderer, &rect);
  // Only on boxes big enough to keep a colour inside the outline.
  if (rect.w >= 4.0f && rect.h >= 4.0f) {
    set_colour(renderer, kBoxOutline);
    SDL_RenderDrawRectF(renderer, &rect);
  }
}

void fill_circle(SDL_Renderer* renderer, const Camera& camera, client::Vec2 centre, double radius,
                 Rgb colour) {
  const PixelPoint c = camera.to_pixel(centre);
  const double r = radius * camera.scale;
  if (r < 1.0) {
    set_colour(renderer, colour);
    SDL_RenderDrawPointF(renderer, to_float(c.x), to_float(c.y));
    return;
  }
  // A triangle fan; enough segments that the edge is within a quarter pixel.
  const int segments =
      std::clamp(static_cast<int>(std::ceil(std::numbers::pi * std::sqrt(r * 2.0))), 12, 128);
  std::vector<SDL_Vertex> vertices;
  vertices.reserve(static_cast<std::size_t>(segments) * 3);
  const SDL_Color fill = sdl(colour);
  const SDL_Vertex middle{{to_float(c.x), to_float(c.y)}, fill, {0.0f, 0.0f}};
  auto rim = [&](int i) {
    const double angle = 2.0 * std::numbers::pi * i / segments;
    return SDL_Vertex{{to_float(c.x + r * std::cos(angle)), to_float(c.y + r * std::sin(angle))},
                      fill,
                      {0.0f, 0.0f}};
  };
  for (int i = 0; i < segments; ++i) {
    vertices.push_back(middle);
    vertices.push_back(rim(i));
    vertices.push_back(rim(i + 1));
  }
  SDL_RenderGeometry(renderer, nullptr, vertices.data(), static_cast<int>(vertices.size()), nullptr,
                     0);
}

void fill_shape(SDL_Renderer* renderer, const Camera& camera, const client::BodyShape& shape,
                client::Vec2 at, Rgb colour) {
  if (shape.shape == client::ShapeType::Box) {
    fill_box(renderer, camera, at, shape.half_extents, colour);
  } else {
    fill_circle(renderer, camera, at, shape.radius, colour);
  }
}

// stb_easy_font indexes a table by character: only printable ASCII may reach it.
std::string printable(const std::string& text) {
  std::string out = text;
  for (char& c : out)
    if (c < 32 || c > 126) c = '?';
  return out;
}

}  // namespace

Rgb dynamic_colour(const client::PlayoutBody& body, std::optional<std::uint64_t> followed) {
  if (followed && *followed == body.body_id) return kFollowed;
  return body.still ? kSleeping : kDynamic;
}

void draw_world(SDL_Renderer* renderer, const Camera& camera, const WorldShapes& shapes,
                const client::PlayoutFrame& frame, std::optional<std::uint64_t> followed) {
  SDL_SetRenderDrawBlendMode(renderer, SDL_BLENDMODE_NONE);
  set_colour(renderer, kBackground);
  SDL_RenderClear(renderer);
  for (const auto& [id, shape] : shapes.all()) {
    if (shape.is_static) fill_shape(renderer, camera, shape, shape.position, kStatic);
  }
  const client::PlayoutBody* last = nullptr;
  for (const client::PlayoutBody& body : frame.bodies) {
    const client::BodyShape* shape = shapes.find(body.body_id);
    if (shape == nullptr || shape->is_static) continue;
    if (followed && *followed == body.body_id) {
      last = &body;  // drawn on top
      continue;
    }
    fill_shape(renderer, camera, *shape, body.position, dynamic_colour(body, followed));
  }
  if (last != nullptr)
    fill_shape(renderer, camera, *shapes.find(last->body_id), last->position, kFollowed);
}

void draw_panel(SDL_Renderer* renderer, const std::vector<std::string>& raw_lines) {
  std::vector<std::string> lines;
  lines.reserve(raw_lines.size());
  for (const std::string& line : raw_lines) lines.push_back(printable(line));
  constexpr float kScale = 2.0f;
  constexpr float kLine = 12.0f;  // stb_easy_font's line height, unscaled
  constexpr float kMargin = 6.0f;
  int widest = 0;
  for (const std::string& line : lines)
    widest = std::max(widest, stb_easy_font_width(const_cast<char*>(line.c_str())));
  SDL_SetRenderDrawBlendMode(renderer, SDL_BLENDMODE_BLEND);
  set_colour(renderer, kPanel, kPanelAlpha);
  const SDL_FRect panel{0.0f, 0.0f, static_cast<float>(widest) * kScale + 2.0f * kMargin,
                        static_cast<float>(lines.size()) * kLine * kScale + 2.0f * kMargin};
  SDL_RenderFillRectF(renderer, &panel);
  SDL_SetRenderDrawBlendMode(renderer, SDL_BLENDMODE_NONE);
  set_colour(renderer, kText);
  // stb_easy_font emits axis-aligned quads: 4 vertices of 16 bytes (x, y, z, colour).
  alignas(16) static char buffer[64 * 1024];
  std::vector<SDL_FRect> rects;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int quads = stb_easy_font_print(0.0f, 0.0f, const_cast<char*>(lines[i].c_str()), nullptr,
                                          buffer, sizeof(buffer));
    rects.clear();
    for (int q = 0; q < quads; ++q) {
      const float* v = reinterpret_cast<const float*>(buffer + q * 64);
      const float x0 = v[0];
      const float y0 = v[1];
      const float x1 = v[8];
      const float y1 = v[9];
      rects.push_back({kMargin + x0 * kScale,
                       kMargin + (static_cast<float>(i) * kLine + y0) * kScale, (x1 - x0) * kScale,
                       (y1 - y0) * kScale});
    }
    SDL_RenderFillRectsF(renderer, rects.data(), static_cast<int>(rects.size()));
  }
}

std::optional<std::uint64_t> body_at(const Camera& camera, const WorldShapes& shapes,
                                     const client::PlayoutFrame& frame, PixelPoint at) {
  const client::Vec2 p = camera.to_world(at);
  std::optional<std::uint64_t> hit;
  for (const client::PlayoutBody& body : frame.bodies) {
    const client::BodyShape* shape = shapes.find(body.body_id);
    if (shape == nullptr) continue;
    const double dx = p.x - body.position.x;
    const double dy = p.y - body.position.y;
    const bool inside =
        shape->shape == client::ShapeType::Box
            ? std::abs(dx) <= shape->half_extents.x && std::abs(dy) <= shape->half_extents.y
            : dx * dx + dy * dy <= shape->radius * shape->radius;
    if (inside) hit = body.body_id;
  }
  return hit;
}

}  // namespace viewer
