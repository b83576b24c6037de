#include "server/token_source.h"

#include <fstream>

namespace server {
namespace {

void strip_line_end(std::string& text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
}

}  // namespace

TokenChoice choose_token(const TokenSources& sources) {
  TokenChoice choice;
  if (!sources.flag.empty() && !sources.file.empty()) {
    choice.error = "give --token or --token-file, not both";
    return choice;
  }
  if (!sources.flag.empty()) {
    choice.token = sources.flag;
    return choice;
  }
  if (!sources.file.empty()) {
    std::ifstream in(sources.file);
    std::string line;
    if (!in || !std::getline(in, line)) {
      choice.error = "cannot read a token from " + sources.file;
      return choice;
    }
    strip_line_end(line);
    if (line.empty()) {
      choice.error = "the first line of " + sources.file + " is empty: no token";
      return choice;
    }
    choice.token = line;
    return choice;
  }
  if (sources.env != nullptr) {
    std::string value = sources.env;
    strip_line_end(value);
    if (value.empty()) {
      choice.error = "PHYSICS_TOKEN is set but empty";
      return choice;
    }
    choice.token = value;
  }
  return choice;
}

}  // namespace server
