#pragma once
// Ticket key files: the key as 64 hexadecimal digits on the first line, readable by
// the file's owner only. physics-ticket --new-key writes one; physics-server
// --ticket-key-file and physics-ticket --key-file read it; a backend in another
// language reads the same line.
#include <string>
#include <string_view>

#include "ticket/ticket.h"

namespace ticket {

std::string key_to_hex(const Key& key);
// False for anything but exactly 64 hexadecimal digits.
bool key_from_hex(std::string_view hex, Key& key);

// Reads the key from `path`; empty, or what was wrong.
std::string read_key_file(const std::string& path, Key& key);
// Writes `key` to a new file `path` with mode 0600; refuses an existing file.
// Empty, or what was wrong.
std::string write_key_file(const std::string& path, const Key& key);

}  // namespace ticket
