#pragma once
// A CLI11 check for a number flag that also refuses NaN: CLI::Range lets NaN through
// (every comparison with it is false), and a NaN friction or width would run a
// whole scene on garbage. Shared by the bench tools.
#include <CLI/CLI.hpp>
#include <charconv>
#include <sstream>
#include <string>

namespace bench {

// Accepts a decimal number in [lo, hi]; anything else (NaN, inf, text, trailing
// characters, out of range) gets "<what> must be a number from <lo> to <hi>, not <text>".
inline CLI::Validator finite_range(const std::string& what, double lo, double hi) {
  std::ostringstream range;
  range << lo << " to " << hi;
  const std::string bounds = range.str();
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double value = 0.0;
        const char* end = text.c_str() + text.size();
        const auto [at, error] = std::from_chars(text.c_str(), end, value);
        if (error != std::errc{} || at != end || !(value >= lo && value <= hi)) {
          return what + " must be a number from " + bounds + ", not " + text;
        }
        return {};
      },
      "NUMBER in [" + bounds + "]");
}

}  // namespace bench
