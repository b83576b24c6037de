#pragma once
// The world-to-pixel mapping. World y points up, pixel y down:
//
//   px = width / 2 + (x - center.x) * scale
//   py = height / 2 - (y - center.y) * scale
//
// so the centre of the view is at pixel (width / 2, height / 2), and a point of
// the world lands in the pixel (floor(px), floor(py)).
#include <vector>

#include "client/types.h"

namespace viewer {

struct PixelPoint {
  double x = 0.0;
  double y = 0.0;
};

struct Camera {
  client::Vec2 center;
  double scale = 20.0;  // pixels per metre
  int width = 1280;
  int height = 720;

  PixelPoint to_pixel(client::Vec2 world) const;
  client::Vec2 to_world(PixelPoint pixel) const;
  // Zooms by `factor` keeping the world point under `pixel` where it is.
  void zoom_at(PixelPoint pixel, double factor);
};

// A camera showing every body of `bodies` (their extents), with a 5% margin; a
// world with no bodies gets 20 px/m around the origin.
Camera fit(const std::vector<client::BodyShape>& bodies, int width, int height);

// Scales are kept within these (pixels per metre).
inline constexpr double kMinScale = 0.01;
inline constexpr double kMaxScale = 100000.0;

}  // namespace viewer
