#include "camera.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace viewer {

PixelPoint Camera::to_pixel(client::Vec2 world) const {
  return {width / 2.0 + (world.x - center.x) * scale, height / 2.0 - (world.y - center.y) * scale};
}

client::Vec2 Camera::to_world(PixelPoint pixel) const {
  return {center.x + (pixel.x - width / 2.0) / scale, center.y - (pixel.y - height / 2.0) / scale};
}

void Camera::zoom_at(PixelPoint pixel, double factor) {
  const client::Vec2 anchor = to_world(pixel);
  scale = std::clamp(scale * factor, kMinScale, kMaxScale);
  // Move the centre so that the anchor maps to the same pixel again.
  center.x = anchor.x - (pixel.x - width / 2.0) / scale;
  center.y = anchor.y + (pixel.y - height / 2.0) / scale;
}

Camera fit(const std::vector<client::BodyShape>& bodies, int width, int height) {
  Camera camera;
  camera.width = width;
  camera.height = height;
  double min_x = std::numeric_limits<double>::infinity();
  double min_y = min_x;
  double max_x = -min_x;
  double max_y = -min_x;
  for (const client::BodyShape& body : bodies) {
    const client::Vec2 h = body.box_half_size();
    if (!std::isfinite(body.position.x) || !std::isfinite(body.position.y)) continue;
    min_x = std::min(min_x, body.position.x - h.x);
    max_x = std::max(max_x, body.position.x + h.x);
    min_y = std::min(min_y, body.position.y - h.y);
    max_y = std::max(max_y, body.position.y + h.y);
  }
  if (!(max_x > min_x) || !(max_y > min_y)) return camera;
  camera.center = {(min_x + max_x) / 2.0, (min_y + max_y) / 2.0};
  const double sx = width / ((max_x - min_x) * 1.05);
  const double sy = height / ((max_y - min_y) * 1.05);
  camera.scale = std::clamp(std::min(sx, sy), kMinScale, kMaxScale);
  return camera;
}

}  // namespace viewer
