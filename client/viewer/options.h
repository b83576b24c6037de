#pragma once
// physics-view's command line (docs/VIEWER.md, Flags).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "client/client.h"
#include "key_map.h"

namespace viewer {

// Exit codes: 0 done, 1 the server could not be reached or the picture not
// written, 2 bad flags (as physics-server).
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

struct ViewerOptions {
  client::ClientConfig client;  // a spectator asking for exact state and the hash
  int width = 1280;
  int height = 720;
  std::optional<double> scale;          // pixels per metre; default: fit the world
  std::optional<client::Vec2> center;   // world point at the centre; default: fit
  std::optional<std::uint64_t> follow;  // body id the camera follows
  bool panel = true;
  std::string screenshot;          // a PNG path: headless, one picture, exit
  std::uint64_t after_ticks = 60;  // ticks after joining that the picture shows
  int connect_timeout_ms = 5000;
  int screenshot_timeout_ms = 30000;  // waiting for the tick, at most
  std::string replay;                 // a client recording to play instead of joining a server
  double speed = 1.0;                 // with --replay: the playback speed
  // Join as a player and draw the predicting client's render state (its own input
  // shown at once, the others predicted, corrections smoothed).
  bool predict = false;
  // With predict: the game's rules library and its scene, run in the prediction
  // (client/game_rules_loader.h).
  std::string rules_file;
  std::string scene_file;
  // Keys bound to game messages (--key, --keys); any binding makes the viewer join
  // as a player (a spectator may not send game messages), as does --play.
  std::vector<KeyBinding> keys;
};

// Parses argv. On --help or a bad flag returns the exit code (0 or kExitUsage)
// after printing; otherwise nullopt and `options` filled in.
std::optional<int> parse_options(int argc, char** argv, ViewerOptions& options);

}  // namespace viewer
