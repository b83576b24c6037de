#include "options.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace viewer {
namespace {

// "WxH", each in [64, 8192].
std::string check_size(const std::string& text) {
  int width = 0;
  int height = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%dx%d%c", &width, &height, &tail) != 2)
    return "must be WIDTHxHEIGHT, e.g. 1280x720";
  if (width < 64 || width > 8192 || height < 64 || height > 8192)
    return "width and height must be in [64, 8192]";
  return {};
}

// CLI::Range lets NaN through (every comparison with it is false).
std::string check_finite(const std::string& text) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size() && std::isfinite(value)) return {};
  } catch (const std::exception&) {
  }
  return "must be a finite number, not '" + text + "'";
}

}  // namespace

std::optional<int> parse_options(int argc, char** argv, ViewerOptions& options) {
  CLI::App app{"physics-view: watches a physics-server as a spectator and draws every body"};
  options.client.name = "physics-view";
  options.client.spectate = true;
  options.client.view.state_hash = true;
  options.client.view.encoding = client::Encoding::Exact;

  app.add_option("--host", options.client.host, "Server address")->capture_default_str();
  app.add_option("--port", options.client.port, "Server port")->capture_default_str();
  app.add_option("--token", options.client.token, "Access token, when the server wants one");
  std::string encoding = "exact";
  app.add_option("--encoding", encoding,
                 "How snapshots describe the bodies: exact (the default: a body not sent did "
                 "not change), full, or predicted (fewest bytes)")
      ->capture_default_str()
      ->check(CLI::IsMember({"predicted", "exact", "full"}));
  std::string size = "1280x720";
  app.add_option("--size", size, "Window or picture size in pixels, WIDTHxHEIGHT")
      ->capture_default_str()
      ->check(check_size);
  app.add_option("--scale", options.scale, "Pixels per metre (default: fit the world)")
      ->check(check_finite)
      ->check(CLI::Range(0.01, 100000.0));
  std::vector<double> center;
  app.add_option("--center", center, "World point X,Y at the centre (default: fit the world)")
      ->delimiter(',')
      ->expected(2)
      ->check(check_finite)
      ->check(CLI::Range(-1e9, 1e9));
  app.add_option("--follow", options.follow, "Body id the camera follows (0: none)");
  bool no_panel = false;
  app.add_flag("--no-panel", no_panel, "Hide the panel of tick, hash, bandwidth and clients");
  auto* shot = app.add_option("--screenshot", options.screenshot,
                              "Headless: write one picture to this PNG file and exit");
  app.add_option("--after-ticks", options.after_ticks,
                 "With --screenshot: the picture shows the first snapshot this many ticks "
                 "after joining")
      ->capture_default_str()
      ->check(CLI::Range(std::uint64_t{0}, std::uint64_t{10000000}))
      ->needs(shot);
  app.add_option("--screenshot-timeout-ms", options.screenshot_timeout_ms,
                 "With --screenshot: give up when the tick has not come after this long")
      ->capture_default_str()
      ->check(CLI::Range(1, 3600000))
      ->needs(shot);
  app.add_option("--connect-timeout-ms", options.connect_timeout_ms,
                 "How long to wait for the connection and the Welcome")
      ->capture_default_str()
      ->check(CLI::Range(1, 600000));

  app.add_option("--record", options.client.record_path,
                 "Also write every message received to FILE, a client recording that "
                 "--replay plays (docs/REPLAY.md)");
  auto* replay = app.add_option("--replay", options.replay,
                                "Play a client recording (physics-view or physics-client "
                                "--record) instead of joining a server")
                     ->check(CLI::ExistingFile);
  auto* predict =
      app.add_flag("--predict", options.predict,
                   "Join as a player and draw what the predicting client shows it (the input "
                   "relay, the world run here; client/predicting_client.h) instead of watching")
          ->excludes(replay);
  auto* rules = app.add_option("--rules", options.rules_file,
                               "With --predict: run this game's rules library (the one "
                               "physics-server --rules runs) in the prediction, so that the "
                               "game's messages show at once")
                    ->check(CLI::ExistingFile)
                    ->needs(predict);
  app.add_option("--scene", options.scene_file,
                 "With --rules: the game's scene file the rules are made for (default: the "
                 "built-in scene)")
      ->check(CLI::ExistingFile)
      ->needs(rules);
  app.add_option("--speed", options.speed, "With --replay: playback speed, in [1/64, 64]")
      ->capture_default_str()
      ->check(check_finite)
      ->check(CLI::Range(1.0 / 64.0, 64.0))
      ->needs(replay);

  std::vector<std::string> key_flags;
  app.add_option("--key", key_flags,
                 "Bind a key to a game message, KEY=PAYLOAD (e.g. space=jump); "
                 "repeatable. Keys: a-z, 0-9, space, return, enter, tab, "
                 "backspace, up, down, left, right, f1-f12. Joins as a player")
      ->excludes(replay);
  std::string key_file;
  app.add_option("--keys", key_file,
                 "Bind keys to game messages from FILE: a KEY=PAYLOAD a line, "
                 "'#' comments. Joins as a player")
      ->check(CLI::ExistingFile)
      ->excludes(replay);
  bool play = false;
  app.add_flag("--play", play,
               "Join as a player (a zero input every tick; the own body ringed) instead of "
               "watching")
      ->excludes(replay);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? 0 : kExitUsage;
  }
  if (!options.screenshot.empty()) {
    const std::string& path = options.screenshot;
    if (path.size() < 4 || path.compare(path.size() - 4, 4, ".png") != 0) {
      std::fprintf(stderr, "physics-view: --screenshot: the file name must end in .png\n");
      return kExitUsage;
    }
  }
  std::string error;
  if (!key_file.empty() && !read_key_map(key_file, options.keys, error)) {
    std::fprintf(stderr, "physics-view: --keys: %s\n", error.c_str());
    return kExitUsage;
  }
  for (const std::string& text : key_flags) {
    std::optional<KeyBinding> binding = parse_key_binding(text, error);
    if (!binding || !add_binding(options.keys, std::move(*binding), error)) {
      std::fprintf(stderr, "physics-view: --key: %s\n", error.c_str());
      return kExitUsage;
    }
  }
  if (play || !options.keys.empty()) options.client.spectate = false;
  std::sscanf(size.c_str(), "%dx%d", &options.width, &options.height);
  if (center.size() == 2) options.center = client::Vec2{center[0], center[1]};
  if (options.follow && *options.follow == 0) options.follow.reset();
  options.panel = !no_panel;
  options.client.view.encoding = encoding == "full"        ? client::Encoding::Full
                                 : encoding == "predicted" ? client::Encoding::Predicted
                                                           : client::Encoding::Exact;
  return std::nullopt;
}

}  // namespace viewer
