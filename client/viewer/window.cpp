#include "window.h"

#include <SDL.h>

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "draw.h"

namespace viewer {

Camera initial_camera(const ViewerOptions& options, const WorldShapes& shapes) {
  Camera camera = fit(shapes.list(), options.width, options.height);
  if (options.scale) camera.scale = *options.scale;
  if (options.center) camera.center = *options.center;
  return camera;
}

void follow(Camera& camera, const client::PlayoutFrame& frame, std::optional<std::uint64_t> id) {
  if (!id) return;
  for (const client::PlayoutBody& body : frame.bodies)
    if (body.body_id == *id) camera.center = body.position;
}

namespace {

// The next dynamic body after `current` in id order (wrapping), for the F key.
std::optional<std::uint64_t> next_body(const client::PlayoutFrame& frame,
                                       std::optional<std::uint64_t> current) {
  if (frame.bodies.empty()) return std::nullopt;
  for (const client::PlayoutBody& body : frame.bodies)
    if (!current || body.body_id > *current) return body.body_id;
  return frame.bodies.front().body_id;
}

// "game keys: space jump  x shoot", the payloads cut to fit a line.
std::string game_keys_help(const std::vector<KeyBinding>& keys) {
  std::string line = "game keys:";
  for (const KeyBinding& binding : keys)
    line.append("  ").append(binding.name).append(" ").append(binding.payload.substr(0, 24));
  return line;
}

}  // namespace

int run_window(const ViewerOptions& options, WorldSource& source, double (*clock)()) {
  SDL_Window* window =
      SDL_CreateWindow("physics-view", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED,
                       options.width, options.height, SDL_WINDOW_RESIZABLE);
  SDL_Renderer* renderer =
      window == nullptr
          ? nullptr
          : SDL_CreateRenderer(window, -1, SDL_RENDERER_ACCELERATED | SDL_RENDERER_PRESENTVSYNC);
  if (renderer == nullptr && window != nullptr)
    renderer = SDL_CreateRenderer(window, -1, SDL_RENDERER_SOFTWARE);
  if (renderer == nullptr) {
    std::fprintf(stderr, "physics-view: cannot open a window: %s\n", SDL_GetError());
    if (window != nullptr) SDL_DestroyWindow(window);
    return kExitFailure;
  }
  Camera camera = initial_camera(options, source.shapes());
  std::optional<std::uint64_t> followed = options.follow;
  bool panel = options.panel;
  bool dragging = false;
  bool running = true;
  const client::PlayoutFrame* frame = &source.update(clock());
  while (running) {
    SDL_Event event;
    while (SDL_PollEvent(&event)) {
      switch (event.type) {
        case SDL_QUIT:
          running = false;
          break;
        case SDL_WINDOWEVENT:
          if (event.window.event == SDL_WINDOWEVENT_SIZE_CHANGED) {
            camera.width = event.window.data1;
            camera.height = event.window.data2;
          }
          break;
        case SDL_MOUSEWHEEL: {
          int x = 0;
          int y = 0;
          SDL_GetMouseState(&x, &y);
          camera.zoom_at({static_cast<double>(x), static_cast<double>(y)},
                         event.wheel.y > 0 ? 1.25 : 0.8);
          break;
        }
        case SDL_MOUSEBUTTONDOWN:
          if (event.button.button == SDL_BUTTON_LEFT) {
            const auto hit =
                body_at(camera, source.shapes(), *frame,
                        {static_cast<double>(event.button.x), static_cast<double>(event.button.y)});
            if (hit) {
              followed = hit;
            } else {
              dragging = true;
            }
          }
          break;
        case SDL_MOUSEBUTTONUP:
          if (event.button.button == SDL_BUTTON_LEFT) dragging = false;
          break;
        case SDL_MOUSEMOTION:
          if (dragging) {
            followed.reset();
            camera.center.x -= event.motion.xrel / camera.scale;
            camera.center.y += event.motion.yrel / camera.scale;
          }
          break;
        case SDL_KEYDOWN: {
          if (const KeyBinding* bound = find_binding(options.keys, event.key.keysym.sym)) {
            if (event.key.repeat == 0) source.send_game_message(bound->payload);
            break;
          }
          if (source.key(event.key.keysym.sym)) break;
          const double step = 0.1 * camera.width / camera.scale;
          switch (event.key.keysym.sym) {
            case SDLK_q:
              running = false;
              break;
            case SDLK_LEFT:
            case SDLK_a:
              followed.reset();
              camera.center.x -= step;
              break;
            case SDLK_RIGHT:
            case SDLK_d:
              followed.reset();
              camera.center.x += step;
              break;
            case SDLK_UP:
            case SDLK_w:
              followed.reset();
              camera.center.y += step;
              break;
            case SDLK_DOWN:
            case SDLK_s:
              followed.reset();
              camera.center.y -= step;
              break;
            case SDLK_PLUS:
            case SDLK_EQUALS:
            case SDLK_KP_PLUS:
              camera.zoom_at({camera.width / 2.0, camera.height / 2.0}, 1.25);
              break;
            case SDLK_MINUS:
            case SDLK_KP_MINUS:
              camera.zoom_at({camera.width / 2.0, camera.height / 2.0}, 0.8);
              break;
            case SDLK_f:
              followed = next_body(*frame, followed);
              break;
            case SDLK_ESCAPE:
              followed.reset();
              break;
            case SDLK_r:
            case SDLK_HOME: {
              const int width = camera.width;
              const int height = camera.height;
              camera = fit(source.shapes().list(), width, height);
              followed.reset();
              break;
            }
            case SDLK_h:
              panel = !panel;
              break;
            default:
              break;
          }
          break;
        }
        default:
          break;
      }
    }
    frame = &source.update(clock());
    follow(camera, *frame, followed);
    draw_world(renderer, camera, source.shapes(), *frame, followed, source.own_body());
    if (panel) {
      std::vector<std::string> lines = source.panel(*frame, followed);
      lines.push_back(
          "drag/arrows pan  wheel/+- zoom  click/F follow  Esc unfollow  R fit  H panel  Q quit");
      if (!source.keys_help().empty()) lines.push_back(source.keys_help());
      if (!options.keys.empty()) lines.push_back(game_keys_help(options.keys));
      draw_panel(renderer, lines);
    }
    SDL_RenderPresent(renderer);
    SDL_Delay(1);  // without vsync, leave the machine's other work a little room
  }
  SDL_DestroyRenderer(renderer);
  SDL_DestroyWindow(window);
  return 0;
}

}  // namespace viewer
