#pragma once
// docs/PROTOCOL.md as the tests read it: the worked byte examples are taken from the
// page itself, so that the page and the wire cannot drift apart.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace protocol_page {

inline std::string text() {
  std::ifstream in(PHYSICS_DOCS_DIR "/PROTOCOL.md");
  std::stringstream page;
  page << in.rdbuf();
  return page.str();
}

// Every "On the wire: `...`" of the page, in order.
inline std::vector<std::string> wire_examples(const std::string& page) {
  std::vector<std::string> found;
  const std::string marker = "On the wire: `";
  for (std::size_t at = page.find(marker); at != std::string::npos;
       at = page.find(marker, at + 1)) {
    const std::size_t start = at + marker.size();
    found.push_back(page.substr(start, page.find('`', start) - start));
  }
  return found;
}

// "0a 07 ...": bytes as the page writes them.
inline std::string hex(const std::string& bytes) {
  std::string out;
  for (const char c : bytes) {
    char buffer[4];
    std::snprintf(buffer, sizeof buffer, "%02x ", static_cast<unsigned char>(c));
    out += buffer;
  }
  if (!out.empty()) out.pop_back();
  return out;
}

}  // namespace protocol_page
