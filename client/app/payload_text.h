#pragma once
// A game message's payload (bytes of the game's own) as physics-client prints it:
// as text when it is well-formed UTF-8, else as base64 (RFC 4648, with padding).
#include <string>
#include <string_view>

namespace client_app {

bool is_utf8(std::string_view bytes);
std::string base64(std::string_view bytes);

}  // namespace client_app
