#pragma once
// physics-netbench's --csv file, opened with its header line written.
#include <fmt/format.h>

#include <cstdio>
#include <string>
#include <string_view>

// The file (nullptr for an empty path: no CSV asked for), or false in `ok` with the
// reason on stderr when it cannot be written.
struct CsvOut {
  std::FILE* file = nullptr;
  bool ok = true;
};

inline CsvOut open_csv(const std::string& path, std::string_view header) {
  CsvOut out;
  if (path.empty()) return out;
  out.file = std::fopen(path.c_str(), "w");
  if (out.file == nullptr) {
    fmt::print(stderr, "physics-netbench: cannot write {}\n", path);
    out.ok = false;
    return out;
  }
  fmt::print(out.file, "{}", header);
  return out;
}
