// physics-view: watches a physics-server as a spectator and draws every body,
// interpolated through the client library's playout buffer, or plays a client
// recording again, or joins as a player and draws what the predicting client
// shows (docs/VIEWER.md).
#include <SDL.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <variant>

#include "client/client_recording.h"
#include "client/game_rules_loader.h"
#include "draw.h"
#include "live_world.h"
#include "options.h"
#include "png.h"
#include "predicted_world.h"
#include "replay_world.h"
#include "window.h"

namespace {

using viewer::ViewerOptions;
using viewer::WorldSource;

double steady_seconds() {
  static const auto start = std::chrono::steady_clock::now();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Draws `frame` headless, writes the picture and prints what it shows.
int write_screenshot(const ViewerOptions& options, const WorldSource& source,
                     const client::PlayoutFrame& frame, std::uint64_t tick, double kbits) {
  viewer::Camera camera = viewer::initial_camera(options, source.shapes());
  viewer::follow(camera, frame, options.follow);
  viewer::OffscreenCanvas canvas(options.width, options.height);
  if (!canvas.ok()) {
    std::fprintf(stderr, "physics-view: %s\n", canvas.error().c_str());
    return viewer::kExitFailure;
  }
  const auto draw_start = std::chrono::steady_clock::now();
  viewer::draw_world(canvas.renderer(), camera, source.shapes(), frame, options.follow,
                     source.own_body());
  if (options.panel) viewer::draw_panel(canvas.renderer(), source.panel(frame, options.follow));
  SDL_RenderFlush(canvas.renderer());
  const double draw_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - draw_start)
          .count();
  const std::string failed = canvas.write_png(options.screenshot);
  if (!failed.empty()) {
    std::fprintf(stderr, "physics-view: %s\n", failed.c_str());
    return viewer::kExitFailure;
  }
  // One line that says what the picture shows, for scripts and tests.
  std::printf(
      "screenshot %s tick %llu size %dx%d scale %.17g center %.17g,%.17g bodies %zu "
      "draw_ms %.2f kbit_s %.1f\n",
      options.screenshot.c_str(), static_cast<unsigned long long>(tick), camera.width,
      camera.height, camera.scale, camera.center.x, camera.center.y, frame.bodies.size(), draw_ms,
      kbits);
  return 0;
}

int run_live_screenshot(const ViewerOptions& options) {
  viewer::LiveWorld world(options.client);
  if (!world.connect(std::chrono::milliseconds(options.connect_timeout_ms))) {
    std::fprintf(stderr, "physics-view: cannot join: %s\n", world.error().c_str());
    return viewer::kExitFailure;
  }
  const std::uint64_t target = world.welcome().current_tick + options.after_ticks;
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(options.screenshot_timeout_ms);
  for (;;) {
    const client::Snapshot* newest = world.buffer().newest();
    if (newest != nullptr && newest->tick >= target) break;
    if (!world.connected()) {
      std::fprintf(stderr, "physics-view: the session ended before tick %llu: %s\n",
                   static_cast<unsigned long long>(target), world.error().c_str());
      return viewer::kExitFailure;
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      std::fprintf(stderr, "physics-view: no snapshot of tick %llu or later within %d ms\n",
                   static_cast<unsigned long long>(target), options.screenshot_timeout_ms);
      return viewer::kExitFailure;
    }
    world.pump(std::chrono::milliseconds(100));
  }
  // The picture shows the newest snapshot exactly: the playout buffer at its tick.
  const std::uint64_t tick = world.buffer().newest()->tick;
  const client::PlayoutFrame& frame =
      world.buffer().state_at_server_time(static_cast<double>(tick) / world.welcome().tick_rate);
  return write_screenshot(options, world, frame, tick, world.kbits_per_second());
}

int run_live_window(const ViewerOptions& options) {
  if (SDL_Init(SDL_INIT_VIDEO) != 0) {
    std::fprintf(stderr,
                 "physics-view: cannot open a window: %s (--screenshot FILE.png needs no "
                 "display)\n",
                 SDL_GetError());
    return viewer::kExitFailure;
  }
  viewer::LiveWorld world(options.client);
  int code = viewer::kExitFailure;
  if (world.connect(std::chrono::milliseconds(options.connect_timeout_ms))) {
    code = viewer::run_window(options, world, steady_seconds);
  } else {
    std::fprintf(stderr, "physics-view: cannot join: %s\n", world.error().c_str());
  }
  SDL_Quit();
  return code;
}

int run_predicted(const ViewerOptions& options) {
  std::shared_ptr<server::GameRules> rules;
  if (!options.rules_file.empty()) {
    std::string why;
    const client::RulesMaker make =
        client::load_game_rules(options.rules_file, options.scene_file, &why);
    if (!make) {
      std::fprintf(stderr, "physics-view: --rules: %s\n", why.c_str());
      return viewer::kExitUsage;
    }
    rules = make();
  }
  viewer::PredictedWorld world(options.client, std::move(rules));
  if (!world.connect(std::chrono::milliseconds(options.connect_timeout_ms))) {
    std::fprintf(stderr, "physics-view: cannot join: %s\n", world.error().c_str());
    return viewer::kExitFailure;
  }
  if (options.screenshot.empty()) {
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
      std::fprintf(stderr, "physics-view: cannot open a window: %s\n", SDL_GetError());
      return viewer::kExitFailure;
    }
    const int code = viewer::run_window(options, world, steady_seconds);
    SDL_Quit();
    return code;
  }
  // The picture shows the prediction once it stands this many ticks past the Welcome.
  const std::uint64_t target = world.client().welcome().current_tick + options.after_ticks;
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(options.screenshot_timeout_ms);
  while (world.client().core().predicted_tick() < target) {
    if (!world.connected()) {
      std::fprintf(stderr, "physics-view: the session ended before tick %llu: %s\n",
                   static_cast<unsigned long long>(target), world.error().c_str());
      return viewer::kExitFailure;
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      std::fprintf(stderr, "physics-view: no prediction of tick %llu within %d ms\n",
                   static_cast<unsigned long long>(target), options.screenshot_timeout_ms);
      return viewer::kExitFailure;
    }
    world.pump(std::chrono::steady_clock::now() + std::chrono::milliseconds(100));
  }
  const client::PlayoutFrame& frame = world.frame();
  return write_screenshot(options, world, frame, world.client().core().predicted_tick(), 0.0);
}

int run_replay(const ViewerOptions& options) {
  auto read = client::read_client_recording(options.replay);
  if (const auto* error = std::get_if<std::string>(&read)) {
    std::fprintf(stderr, "physics-view: cannot replay %s: %s\n", options.replay.c_str(),
                 error->c_str());
    return viewer::kExitFailure;
  }
  client::ClientRecording recording = std::get<client::ClientRecording>(std::move(read));
  if (recording.snapshots.empty()) {
    std::fprintf(stderr, "physics-view: cannot replay %s: it holds no snapshot\n",
                 options.replay.c_str());
    return viewer::kExitFailure;
  }
  const std::uint64_t target = recording.welcome.current_tick + options.after_ticks;
  viewer::ReplayWorld replay(std::move(recording), options.replay, options.speed);
  if (!options.screenshot.empty()) {
    replay.seek_tick(target);
    replay.set_paused(true);
    const client::PlayoutFrame& frame = replay.update(0.0);
    return write_screenshot(options, replay, frame, replay.current().tick, 0.0);
  }
  if (SDL_Init(SDL_INIT_VIDEO) != 0) {
    std::fprintf(stderr, "physics-view: cannot open a window: %s\n", SDL_GetError());
    return viewer::kExitFailure;
  }
  const int code = viewer::run_window(options, replay, steady_seconds);
  SDL_Quit();
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  ViewerOptions options;
  if (const auto exit_code = viewer::parse_options(argc, argv, options)) return *exit_code;
  if (!options.replay.empty()) return run_replay(options);
  if (options.predict) return run_predicted(options);
  return options.screenshot.empty() ? run_live_window(options) : run_live_screenshot(options);
}
