#pragma once
// The bench tools' command line, parsed as every executable of the product does
// (README, "The executables"): --help prints and exits 0, a bad flag says why on
// stderr and exits 2. CLI11_PARSE would return CLI11's own codes (109 and so on).
#include <CLI/CLI.hpp>
#include <optional>

namespace bench {

inline constexpr int kExitUsage = 2;

// The exit code when the program should stop here (help asked, or a bad flag);
// nullopt when the flags are good.
inline std::optional<int> parse_flags(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error) == 0 ? 0 : kExitUsage;
  }
  return std::nullopt;
}

}  // namespace bench
