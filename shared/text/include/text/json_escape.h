#pragma once
// Bytes -> the inside of a JSON string (RFC 8259), for every program of ours that
// writes JSON by hand: the server's JSON logs, physics-client --json, physics-sim
// --json.
#include <string>
#include <string_view>

namespace text {

// `raw` escaped to sit between the quotes of a JSON string, always valid UTF-8:
//  - `"` and `\` are escaped with a backslash;
//  - control characters (below 0x20) as \n, \r, \t or \u00XX;
//  - well-formed UTF-8 (any code point, DEL included) is copied as it is;
//  - a byte that is not part of a well-formed UTF-8 sequence becomes \ufffd (the
//    replacement character), one for each maximal ill-formed subpart as Unicode
//    recommends: a JSON reader refuses invalid UTF-8, so one stray byte in a log
//    message would otherwise make the whole line unreadable.
std::string json_escape(std::string_view raw);

}  // namespace text
