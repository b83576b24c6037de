#include "png.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <cstdint>
#include <cstring>
#include <vector>

namespace viewer {

OffscreenCanvas::OffscreenCanvas(int width, int height) {
  surface_ = SDL_CreateRGBSurfaceWithFormat(0, width, height, 32, SDL_PIXELFORMAT_RGBA32);
  if (surface_ == nullptr) {
    error_ = std::string("cannot make a surface: ") + SDL_GetError();
    return;
  }
  renderer_ = SDL_CreateSoftwareRenderer(surface_);
  if (renderer_ == nullptr)
    error_ = std::string("cannot make a software renderer: ") + SDL_GetError();
}

OffscreenCanvas::~OffscreenCanvas() {
  if (renderer_ != nullptr) SDL_DestroyRenderer(renderer_);
  if (surface_ != nullptr) SDL_FreeSurface(surface_);
}

std::string OffscreenCanvas::write_png(const std::string& path) {
  if (!ok()) return error_;
  SDL_RenderPresent(renderer_);  // runs the batched drawing onto the surface
  const int width = surface_->w;
  const int height = surface_->h;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
  if (SDL_MUSTLOCK(surface_)) SDL_LockSurface(surface_);
  // SDL_PIXELFORMAT_RGBA32 is bytes R, G, B, A in memory on every machine.
  const auto* pixels = static_cast<const std::uint8_t*>(surface_->pixels);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* row = pixels + static_cast<std::ptrdiff_t>(y) * surface_->pitch;
    std::uint8_t* out = rgb.data() + static_cast<std::size_t>(y) * width * 3;
    for (int x = 0; x < width; ++x) std::memcpy(out + x * 3, row + x * 4, 3);
  }
  if (SDL_MUSTLOCK(surface_)) SDL_UnlockSurface(surface_);
  if (stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3) == 0)
    return "cannot write " + path;
  return {};
}

}  // namespace viewer
