// text::json_escape: every byte string becomes the inside of a valid JSON string,
// with well-formed UTF-8 kept as it is.
#include "text/json_escape.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>

namespace {

using text::json_escape;

TEST(JsonEscape, PlainTextIsUnchanged) {
  EXPECT_EQ(json_escape(""), "");
  EXPECT_EQ(json_escape("plain text, 42 {} [] / ~\x7f"), "plain text, 42 {} [] / ~\x7f");
}

TEST(JsonEscape, QuotesAndBackslashesAreEscaped) {
  EXPECT_EQ(json_escape("say \"hi\""), "say \\\"hi\\\"");
  EXPECT_EQ(json_escape("C:\\dir\\"), "C:\\\\dir\\\\");
  EXPECT_EQ(json_escape("\\\""), "\\\\\\\"");
}

TEST(JsonEscape, ControlCharactersAreEscaped) {
  EXPECT_EQ(json_escape("a\nb\tc\rd"), "a\\nb\\tc\\rd");
  EXPECT_EQ(json_escape(std::string("\0", 1)), "\\u0000");
  EXPECT_EQ(json_escape("\x01"), "\\u0001");
  EXPECT_EQ(json_escape("\x08\x0c"), "\\u0008\\u000c");
  EXPECT_EQ(json_escape("\x1b[31m"), "\\u001b[31m");
  EXPECT_EQ(json_escape("\x1f"), "\\u001f");
  // Every control character is escaped; nothing below 0x20 is left in the output.
  for (int c = 0; c < 0x20; ++c) {
    const std::string escaped = json_escape(std::string(1, static_cast<char>(c)));
    SCOPED_TRACE(c);
    ASSERT_GE(escaped.size(), 2u);
    EXPECT_EQ(escaped[0], '\\');
    for (const char e : escaped) EXPECT_GE(static_cast<unsigned char>(e), 0x20);
  }
}

TEST(JsonEscape, WellFormedUtf8IsKept) {
  EXPECT_EQ(json_escape("caf\xc3\xa9"), "caf\xc3\xa9");            // U+00E9
  EXPECT_EQ(json_escape("\xe2\x9c\x93"), "\xe2\x9c\x93");          // U+2713
  EXPECT_EQ(json_escape("\xf0\x9f\x8e\xb1"), "\xf0\x9f\x8e\xb1");  // U+1F3B1
  EXPECT_EQ(json_escape("\xed\x9f\xbf"), "\xed\x9f\xbf");          // U+D7FF
  EXPECT_EQ(json_escape("\xee\x80\x80"), "\xee\x80\x80");          // U+E000
  EXPECT_EQ(json_escape("\xf4\x8f\xbf\xbf"), "\xf4\x8f\xbf\xbf");  // U+10FFFF
  EXPECT_EQ(json_escape("\xc2\x80\xdf\xbf"), "\xc2\x80\xdf\xbf");  // U+0080, U+07FF
  EXPECT_EQ(json_escape("\"\xc3\xa9\"\n"), "\\\"\xc3\xa9\\\"\\n");
}

TEST(JsonEscape, IllFormedUtf8BecomesReplacementCharacters) {
  EXPECT_EQ(json_escape("bad\xff"), "bad\\ufffd");
  EXPECT_EQ(json_escape("\x80"), "\\ufffd");                        // a continuation byte alone
  EXPECT_EQ(json_escape("\xc0\xaf"), "\\ufffd\\ufffd");             // overlong '/'
  EXPECT_EQ(json_escape("\xe0\x80\xaf"), "\\ufffd\\ufffd\\ufffd");  // overlong, 3 bytes
  EXPECT_EQ(json_escape("\xed\xa0\x80"), "\\ufffd\\ufffd\\ufffd");  // surrogate U+D800
  EXPECT_EQ(json_escape("\xf4\x90\x80\x80"), "\\ufffd\\ufffd\\ufffd\\ufffd");  // > U+10FFFF
  EXPECT_EQ(json_escape("\xf5\x80"), "\\ufffd\\ufffd");
  // A sequence cut short is one replacement, and what follows is kept.
  EXPECT_EQ(json_escape("\xe2\x9c"), "\\ufffd");
  EXPECT_EQ(json_escape("\xe2\x9c"
                        "A"),
            "\\ufffdA");
  EXPECT_EQ(json_escape("\xf0\x9f\x8e\""), "\\ufffd\\\"");
  EXPECT_EQ(json_escape("\xc3"
                        "caf\xc3\xa9"),
            "\\ufffdcaf\xc3\xa9");
}

// Whether `s` is well-formed UTF-8 with no byte below 0x20, and every quote and
// backslash in it is escaped: what a JSON reader accepts between two quotes.
bool valid_json_string_body(const std::string& s) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x20 || c == '"') return false;
    if (c == '\\') {
      if (i + 1 >= s.size()) return false;
      const char next = s[++i];
      if (next == 'u') {
        if (i + 4 >= s.size()) return false;
        i += 4;
      } else if (std::string("\"\\/bfnrt").find(next) == std::string::npos) {
        return false;
      }
      continue;
    }
    if (c < 0x80) continue;
    // Decode one sequence, by the bit patterns alone, then check the code point.
    const int length = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : c >= 0xc0 ? 2 : 0;
    if (length == 0 || i + static_cast<std::size_t>(length) > s.size()) return false;
    std::uint32_t point = c & (0x7f >> length);
    for (int k = 1; k < length; ++k) {
      const auto next = static_cast<unsigned char>(s[i + static_cast<std::size_t>(k)]);
      if ((next & 0xc0) != 0x80) return false;
      point = (point << 6) | (next & 0x3f);
    }
    const std::uint32_t smallest = length == 2 ? 0x80 : length == 3 ? 0x800 : 0x10000;
    if (point < smallest || point > 0x10ffff || (point >= 0xd800 && point <= 0xdfff)) return false;
    i += static_cast<std::size_t>(length) - 1;
  }
  return true;
}

TEST(JsonEscape, RandomBytesAlwaysGiveAValidString) {
  std::mt19937 random(2024);
  for (int round = 0; round < 5000; ++round) {
    std::string raw(random() % 24, '\0');
    for (char& c : raw) c = static_cast<char>(random() % 256);
    const std::string escaped = json_escape(raw);
    ASSERT_TRUE(valid_json_string_body(escaped)) << "from " << ::testing::PrintToString(raw);
  }
}

}  // namespace
