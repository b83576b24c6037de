#pragma once
// Headless pictures: a software renderer drawing onto a memory surface, and its
// pixels written as a PNG (stb_image_write).
#include <SDL.h>

#include <string>

namespace viewer {

// A software renderer on an RGBA surface of the given size; needs no display.
class OffscreenCanvas {
 public:
  OffscreenCanvas(int width, int height);
  ~OffscreenCanvas();
  OffscreenCanvas(const OffscreenCanvas&) = delete;
  OffscreenCanvas& operator=(const OffscreenCanvas&) = delete;

  bool ok() const { return renderer_ != nullptr; }
  const std::string& error() const { return error_; }
  SDL_Renderer* renderer() const { return renderer_; }
  // Writes what was drawn as an RGB PNG. Empty on success, else what failed.
  std::string write_png(const std::string& path);

 private:
  SDL_Surface* surface_ = nullptr;
  SDL_Renderer* renderer_ = nullptr;
  std::string error_;
};

}  // namespace viewer
