#include "text/json_escape.h"

#include <cstddef>

namespace text {
namespace {

// The length of the well-formed UTF-8 sequence that starts at `at` (1 to 4), or 0
// when the bytes there are ill-formed; then `*prefix` is how many of them form the
// start of a well-formed sequence (Unicode's "maximal subpart", at least 1).
// The ranges are those of the Unicode Standard, Table 3-7: no overlong forms, no
// surrogates (U+D800..U+DFFF), nothing past U+10FFFF.
std::size_t utf8_sequence(std::string_view raw, std::size_t at, std::size_t* prefix) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(raw[i]); };
  const unsigned char lead = byte(at);
  *prefix = 1;
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  unsigned char second_low = 0x80;
  unsigned char second_high = 0xbf;
  if (lead >= 0xc2 && lead <= 0xdf) {
    length = 2;
  } else if (lead >= 0xe0 && lead <= 0xef) {
    length = 3;
    if (lead == 0xe0) second_low = 0xa0;   // below: overlong
    if (lead == 0xed) second_high = 0x9f;  // above: surrogates
  } else if (lead >= 0xf0 && lead <= 0xf4) {
    length = 4;
    if (lead == 0xf0) second_low = 0x90;   // below: overlong
    if (lead == 0xf4) second_high = 0x8f;  // above: past U+10FFFF
  } else {
    return 0;  // a continuation byte, C0/C1 (always overlong) or F5..FF
  }
  for (std::size_t i = 1; i < length; ++i) {
    if (at + i >= raw.size()) return 0;
    const unsigned char next = byte(at + i);
    const unsigned char low = i == 1 ? second_low : 0x80;
    const unsigned char high = i == 1 ? second_high : 0xbf;
    if (next < low || next > high) return 0;
    *prefix = i + 1;
  }
  return length;
}

}  // namespace

std::string json_escape(std::string_view raw) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(raw.size() + 8);
  std::size_t at = 0;
  while (at < raw.size()) {
    const char c = raw[at];
    const auto code = static_cast<unsigned char>(c);
    if (code >= 0x80) {
      std::size_t prefix = 1;
      const std::size_t length = utf8_sequence(raw, at, &prefix);
      if (length == 0) {
        out += "\\ufffd";
        at += prefix;
      } else {
        out.append(raw.substr(at, length));
        at += length;
      }
      continue;
    }
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (code < 0x20) {
          out += "\\u00";
          out += kHex[code >> 4];
          out += kHex[code & 0xf];
        } else {
          out += c;
        }
    }
    ++at;
  }
  return out;
}

}  // namespace text
