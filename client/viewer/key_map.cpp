#include "key_map.h"

#include <SDL_keycode.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <fstream>

#include "client/game_message_plan.h"

namespace viewer {

std::optional<int> keycode_of(std::string_view raw) {
  std::string name(raw);
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // SDL's keycodes of letters and digits are their ASCII characters.
  if (name.size() == 1 &&
      ((name[0] >= 'a' && name[0] <= 'z') || (name[0] >= '0' && name[0] <= '9')))
    return static_cast<int>(name[0]);
  if (name == "space") return SDLK_SPACE;
  if (name == "return" || name == "enter") return SDLK_RETURN;
  if (name == "tab") return SDLK_TAB;
  if (name == "backspace") return SDLK_BACKSPACE;
  if (name == "up") return SDLK_UP;
  if (name == "down") return SDLK_DOWN;
  if (name == "left") return SDLK_LEFT;
  if (name == "right") return SDLK_RIGHT;
  if (name.size() >= 2 && name.size() <= 3 && name[0] == 'f' &&
      std::all_of(name.begin() + 1, name.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    const int n = std::stoi(name.substr(1));
    if (n >= 1 && n <= 12) return SDLK_F1 + (n - 1);
  }
  return std::nullopt;
}

std::optional<KeyBinding> parse_key_binding(std::string_view text, std::string& error) {
  const std::size_t equals = text.find('=');
  if (equals == std::string_view::npos) {
    error = fmt::format("'{}' is not KEY=PAYLOAD", text);
    return std::nullopt;
  }
  KeyBinding binding;
  binding.name = std::string(text.substr(0, equals));
  binding.payload = std::string(text.substr(equals + 1));
  const std::optional<int> keycode = keycode_of(binding.name);
  if (!keycode) {
    error = fmt::format(
        "unknown key '{}' (a-z, 0-9, space, return, enter, tab, backspace, up, down, left, "
        "right, f1-f12)",
        binding.name);
    return std::nullopt;
  }
  if (binding.payload.empty()) {
    error = fmt::format("key '{}' has no payload", binding.name);
    return std::nullopt;
  }
  if (binding.payload.size() > client::kMaxGameMessageBytes) {
    error = fmt::format("key '{}': a game message holds at most {} bytes; this one has {}",
                        binding.name, client::kMaxGameMessageBytes, binding.payload.size());
    return std::nullopt;
  }
  std::transform(binding.name.begin(), binding.name.end(), binding.name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  binding.keycode = *keycode;
  return binding;
}

bool add_binding(std::vector<KeyBinding>& map, KeyBinding binding, std::string& error) {
  if (find_binding(map, binding.keycode) != nullptr) {
    error = fmt::format("key '{}' is bound twice", binding.name);
    return false;
  }
  map.push_back(std::move(binding));
  return true;
}

bool read_key_map(const std::string& path, std::vector<KeyBinding>& map, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = fmt::format("cannot read {}", path);
    return false;
  }
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::string why;
    std::optional<KeyBinding> binding = parse_key_binding(line, why);
    if (!binding || !add_binding(map, std::move(*binding), why)) {
      error = fmt::format("{}:{}: {}", path, number, why);
      return false;
    }
  }
  return true;
}

const KeyBinding* find_binding(const std::vector<KeyBinding>& map, int keycode) {
  for (const KeyBinding& binding : map)
    if (binding.keycode == keycode) return &binding;
  return nullptr;
}

}  // namespace viewer
