#include "draw.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "text_draw.h"

namespace viewer {
namespace {

void set_colour(SDL_Renderer* renderer, Rgb c, std::uint8_t alpha = 255) {
  // Translucent fills blend over what is drawn already; opaque ones replace it.
  SDL_SetRenderDrawBlendMode(renderer, alpha == 255 ? SDL_BLENDMODE_NONE : SDL_BLENDMODE_BLEND);
  SDL_SetRenderDrawColor(renderer, c.r, c.g, c.b, alpha);
}

float to_float(double value) {
  // Far off-screen coordinates are clamped, so that a huge zoom cannot overflow
  // the renderer's float or int arithmetic.
  return static_cast<float>(std::clamp(value, -1e6, 1e6));
}

SDL_FRect box_rect(const Camera& camera, client::Vec2 centre, client::Vec2 half) {
  const PixelPoint top_left = camera.to_pixel({centre.x - half.x, centre.y + half.y});
  const PixelPoint bottom_right = camera.to_pixel({centre.x + half.x, centre.y - half.y});
  return SDL_FRect{to_float(top_left.x), to_float(top_left.y),
                   to_float(bottom_right.x - top_left.x), to_float(bottom_right.y - top_left.y)};
}

// `edge`: the one-pixel outline inside the box, when it is big enough to keep a
// colour inside it.
void fill_box(SDL_Renderer* renderer, const Camera& camera, client::Vec2 centre, client::Vec2 half,
              Rgb colour, std::uint8_t alpha, Rgb edge) {
  const SDL_FRect rect = box_rect(camera, centre, half);
  set_colour(renderer, colour, alpha);
  SDL_RenderFillRectF(renderer, &rect);
  if (rect.w >= 4.0f && rect.h >= 4.0f) {
    set_colour(renderer, edge);
    SDL_RenderDrawRectF(renderer, &rect);
  }
}

// The rim's points, enough of them that the edge is within a quarter pixel.
std::vector<SDL_FPoint> rim(PixelPoint c, double r) {
  const int segments =
      std::clamp(static_cast<int>(std::ceil(std::numbers::pi * std::sqrt(r * 2.0))), 12, 128);
  std::vector<SDL_FPoint> points;
  points.reserve(static_cast<std::size_t>(segments) + 1);
  for (int i = 0; i <= segments; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / segments;
    points.push_back({to_float(c.x + r * std::cos(angle)), to_float(c.y + r * std::sin(angle))});
  }
  return points;
}

void fill_circle(SDL_Renderer* renderer, const Camera& camera, client::Vec2 centre, double radius,
                 Rgb colour, std::uint8_t alpha) {
  const PixelPoint c = camera.to_pixel(centre);
  const double r = radius * camera.scale;
  set_colour(renderer, colour, alpha);
  if (r < 1.0) {
    SDL_RenderDrawPointF(renderer, to_float(c.x), to_float(c.y));
    return;
  }
  // A triangle fan, blended as the renderer's draw blend mode says.
  const SDL_Color fill{colour.r, colour.g, colour.b, alpha};
  const std::vector<SDL_FPoint> points = rim(c, r);
  std::vector<SDL_Vertex> vertices;
  vertices.reserve(points.size() * 3);
  const SDL_Vertex middle{{to_float(c.x), to_float(c.y)}, fill, {0.0f, 0.0f}};
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    vertices.push_back(middle);
    vertices.push_back({points[i], fill, {0.0f, 0.0f}});
    vertices.push_back({points[i + 1], fill, {0.0f, 0.0f}});
  }
  SDL_RenderGeometry(renderer, nullptr, vertices.data(), static_cast<int>(vertices.size()), nullptr,
                     0);
}

void fill_shape(SDL_Renderer* renderer, const Camera& camera, const client::BodyShape& shape,
                client::Vec2 at, Rgb colour, std::uint8_t alpha = 255) {
  if (shape.shape == client::ShapeType::Box) {
    fill_box(renderer, camera, at, shape.half_extents, colour, alpha,
             alpha == 255 ? kBoxOutline : colour);
  } else {
    fill_circle(renderer, camera, at, shape.radius, colour, alpha);
  }
}

// A two-pixel ring just outside the body.
void draw_ring(SDL_Renderer* renderer, const Camera& camera, const client::BodyShape& shape,
               client::Vec2 at) {
  set_colour(renderer, kOwnMarker);
  for (const float grow : {2.0f, 3.0f}) {
    if (shape.shape == client::ShapeType::Box) {
      SDL_FRect rect = box_rect(camera, at, shape.half_extents);
      rect = {rect.x - grow, rect.y - grow, rect.w + 2.0f * grow, rect.h + 2.0f * grow};
      SDL_RenderDrawRectF(renderer, &rect);
    } else {
      const std::vector<SDL_FPoint> points =
          rim(camera.to_pixel(at), shape.radius * camera.scale + static_cast<double>(grow));
      SDL_RenderDrawLinesF(renderer, points.data(), static_cast<int>(points.size()));
    }
  }
}

void draw_label(SDL_Renderer* renderer, const Camera& camera, const client::BodyShape& shape,
                client::Vec2 at, const std::string& label) {
  const double half_height =
      shape.shape == client::ShapeType::Box ? shape.half_extents.y : shape.radius;
  const PixelPoint top = camera.to_pixel({at.x, at.y + half_height});
  constexpr float kScale = 1.0f;
  const float x = to_float(top.x) - text_width(label, kScale) / 2.0f;
  const float y = to_float(top.y) - (kTextLine + 4.0f) * kScale;
  draw_text(renderer, x, y, kScale, label, kText);
}

}  // namespace

Rgb dynamic_colour(const client::PlayoutBody& body, std::optional<std::uint64_t> followed) {
  if (followed && *followed == body.body_id) return kFollowed;
  return body.still ? kSleeping : kDynamic;
}

std::string body_label(const client::BodyShape& shape, const WorldShapes& shapes,
                       std::optional<std::uint64_t> own) {
  const bool is_own = own && *own == shape.body_id;
  if (!is_own && (!shapes.joined_later(shape.body_id) || shape.is_sensor)) return {};
  std::string label = shape.name.empty() ? fmt::format("#{}", shape.body_id) : shape.name;
  if (is_own) label.append(" (you)");
  return label;
}

void draw_world(SDL_Renderer* renderer, const Camera& camera, const WorldShapes& shapes,
                const client::PlayoutFrame& frame, std::optional<std::uint64_t> followed,
                std::optional<std::uint64_t> own) {
  set_colour(renderer, kBackground);
  SDL_RenderClear(renderer);
  // Where each moving body is drawn: the frame's, else (a kinematic body no snapshot
  // carried) where the Welcome or its adding snapshot put it.
  std::map<std::uint64_t, client::Vec2> at;
  for (const auto& [id, shape] : shapes.all())
    if (!shape.is_static) at[id] = shape.position;
  std::map<std::uint64_t, const client::PlayoutBody*> in_frame;
  for (const client::PlayoutBody& body : frame.bodies) {
    at[body.body_id] = body.position;
    in_frame[body.body_id] = &body;
  }
  for (const auto& [id, shape] : shapes.all())
    if (shape.is_static && !shape.is_sensor)
      fill_shape(renderer, camera, shape, shape.position, kStatic);
  for (const auto& [id, shape] : shapes.all()) {
    if (shape.is_static || shape.is_sensor || (followed && *followed == id)) continue;
    const auto body = in_frame.find(id);
    if (shape.is_kinematic) {
      fill_shape(renderer, camera, shape, at[id], kKinematic);
    } else if (body != in_frame.end()) {
      fill_shape(renderer, camera, shape, at[id], dynamic_colour(*body->second, followed));
    }
  }
  if (followed) {
    const client::BodyShape* shape = shapes.find(*followed);
    if (shape != nullptr && in_frame.count(*followed) != 0)
      fill_shape(renderer, camera, *shape, at[*followed], kFollowed);
  }
  // Sensors last and translucent: what is inside one shows through.
  for (const auto& [id, shape] : shapes.all()) {
    if (shape.is_sensor)
      fill_shape(renderer, camera, shape, shape.is_static ? shape.position : at[id], kSensor,
                 kSensorAlpha);
  }
  if (own) {
    const client::BodyShape* shape = shapes.find(*own);
    if (shape != nullptr && in_frame.count(*own) != 0)
      draw_ring(renderer, camera, *shape, at[*own]);
  }
  for (const auto& [id, shape] : shapes.all()) {
    if (shape.is_static || (!shape.is_kinematic && in_frame.count(id) == 0)) continue;
    const std::string label = body_label(shape, shapes, own);
    if (!label.empty()) draw_label(renderer, camera, shape, at[id], label);
  }
}

void draw_panel(SDL_Renderer* renderer, const std::vector<std::string>& lines) {
  constexpr float kScale = 2.0f;
  constexpr float kMargin = 6.0f;
  float widest = 0.0f;
  for (const std::string& line : lines) widest = std::max(widest, text_width(line, kScale));
  set_colour(renderer, kPanel, kPanelAlpha);
  const SDL_FRect panel{0.0f, 0.0f, widest + 2.0f * kMargin,
                        static_cast<float>(lines.size()) * kTextLine * kScale + 2.0f * kMargin};
  SDL_RenderFillRectF(renderer, &panel);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    draw_text(renderer, kMargin, kMargin + static_cast<float>(i) * kTextLine * kScale, kScale,
              lines[i], kText);
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
