#include "ticket/key_file.h"

#include <fcntl.h>
#include <sodium.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

namespace ticket {

std::string key_to_hex(const Key& key) {
  std::string hex(key.size() * 2 + 1, '\0');
  sodium_bin2hex(hex.data(), hex.size(), key.data(), key.size());
  hex.pop_back();
  return hex;
}

bool key_from_hex(std::string_view hex, Key& key) {
  if (hex.size() != key.size() * 2) return false;
  std::size_t size = 0;
  const char* end = nullptr;
  return sodium_hex2bin(key.data(), key.size(), hex.data(), hex.size(), nullptr, &size, &end) ==
             0 &&
         size == key.size() && end == hex.data() + hex.size();
}

std::string read_key_file(const std::string& path, Key& key) {
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line)) return "cannot read a ticket key from " + path;
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  if (!key_from_hex(line, key)) {
    return "the first line of " + path + " is not a ticket key (64 hexadecimal digits)";
  }
  return {};
}

std::string write_key_file(const std::string& path, const Key& key) {
  // O_EXCL: an existing key is never overwritten, so tickets minted with it stay valid.
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    return errno == EEXIST ? path + " exists: a key file is never overwritten"
                           : "cannot create " + path + ": " + std::strerror(errno);
  }
  const std::string line = key_to_hex(key) + "\n";
  const bool written = ::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size());
  const bool closed = ::close(fd) == 0;
  if (!written || !closed) {
    ::unlink(path.c_str());
    return "cannot write " + path;
  }
  return {};
}

}  // namespace ticket
