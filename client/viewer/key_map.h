#pragma once
// Keys bound to game messages (physics-view --key NAME=PAYLOAD and --keys FILE,
// docs/VIEWER.md "Game keys"): pressing the key sends the payload to the game's
// rules (docs/PROTOCOL.md 3.9) instead of doing the viewer's own action.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace viewer {

struct KeyBinding {
  int keycode = 0;      // an SDL_Keycode
  std::string name;     // as given, lower-cased
  std::string payload;  // 1 to 256 bytes
};

// The names accepted: a to z, 0 to 9, space, return (or enter), tab, backspace, up,
// down, left, right, f1 to f12; any case. nullopt for any other.
std::optional<int> keycode_of(std::string_view name);

// "NAME=PAYLOAD" (the payload is everything after the first '='). On success the
// binding; otherwise nullopt and `error` says why.
std::optional<KeyBinding> parse_key_binding(std::string_view text, std::string& error);

// Adds `binding` to `map`; false (and `error`) when its key is bound already.
bool add_binding(std::vector<KeyBinding>& map, KeyBinding binding, std::string& error);

// A key map file: one NAME=PAYLOAD a line; blank lines and lines starting with '#'
// are skipped. False with `error` naming the line when one does not parse.
bool read_key_map(const std::string& path, std::vector<KeyBinding>& map, std::string& error);

// The binding of `keycode`, if any.
const KeyBinding* find_binding(const std::vector<KeyBinding>& map, int keycode);

}  // namespace viewer
