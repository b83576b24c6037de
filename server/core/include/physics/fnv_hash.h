#pragma once
// FNV-1a, 64-bit, over 64-bit words fed a byte at a time from the lowest: the mixer of
// the world's state hash and of the server's per-body hashes in recordings, so that
// both are spelled once. Doubles go in as their exact bit patterns (copied with
// memcpy, not std::bit_cast, which the libc++ of Debian's emscripten lacks).
#include <cstdint>
#include <cstring>

namespace phys {

class Fnv1a64 {
 public:
  void mix(std::uint64_t word) {
    for (int i = 0; i < 8; ++i) {
      hash_ ^= (word >> (8 * i)) & 0xffu;
      hash_ *= 0x100000001b3ull;
    }
  }
  void mix_double(double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    mix(bits);
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

}  // namespace phys
