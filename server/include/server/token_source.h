#pragma once
// Where physics-server's access token comes from: --token (visible to every user of
// the machine in /proc/PID/cmdline, so for tests only), --token-file (the first
// line of a file), or the PHYSICS_TOKEN environment variable (private to the
// process and its owner in /proc/PID/environ).
#include <optional>
#include <string>

namespace server {

struct TokenSources {
  std::string flag;           // --token, empty when not given
  std::string file;           // --token-file, empty when not given
  const char* env = nullptr;  // getenv("PHYSICS_TOKEN"), null when unset
};

struct TokenChoice {
  std::optional<std::string> token;  // none: the server takes any Hello
  std::string error;                 // non-empty: refuse to start, and say why
};

// At most one of the flag and the file may be given; either wins over the
// environment. A file's first line is the token, without its line ending; an empty
// token (from any source) is an error rather than "no token".
TokenChoice choose_token(const TokenSources& sources);

}  // namespace server
