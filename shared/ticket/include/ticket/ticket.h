#pragma once
// Connect tickets: a game's backend mints one per player with a key it shares with
// the server, and the player's client sends it as Hello.access_token; the server
// admits only holders of a valid ticket. The format (docs/PROTOCOL.md, "Connect
// tickets") is version 1, little-endian, sealed with HMAC-SHA-256, base64url without
// padding:
//   version u8 | flags u8 (bit 0: a seat) | key id [4] | player id u64 | seat u32 |
//   expires_at u64 (unix seconds) | nonce [16] | room length u8 | room bytes |
//   HMAC-SHA-256(key, every byte before it) [32]
// The key id (the first 4 bytes of HMAC-SHA-256(key, "physics ticket key id")) tells
// a ticket minted with another key from one whose bytes were changed.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace ticket {

inline constexpr std::uint8_t kVersion = 1;
inline constexpr std::size_t kKeyBytes = 32;
inline constexpr std::size_t kKeyIdBytes = 4;
inline constexpr std::size_t kNonceBytes = 16;
inline constexpr std::size_t kMacBytes = 32;
inline constexpr std::size_t kMaxRoomBytes = 64;
// The bytes of a ticket without its room: the base64url text is 100 characters then,
// 186 with the longest room.
inline constexpr std::size_t kFixedBytes =
    1 + 1 + kKeyIdBytes + 8 + 4 + 8 + kNonceBytes + 1 + kMacBytes;

using Key = std::array<std::uint8_t, kKeyBytes>;
using KeyId = std::array<std::uint8_t, kKeyIdBytes>;
using Nonce = std::array<std::uint8_t, kNonceBytes>;

struct Ticket {
  std::uint64_t player_id = 0;
  std::optional<std::uint32_t> seat;  // none: the server gives the lowest free seat
  std::string room;                   // none (empty): valid in any room
  std::uint64_t expires_at = 0;       // unix seconds; valid while now < expires_at
  Nonce nonce{};                      // random, so that no two tickets are alike
};

// Why a ticket is refused, in the order the checks run.
enum class Problem {
  None,
  Missing,         // no ticket at all
  Malformed,       // not base64url, or not the length its room says
  UnknownVersion,  // a version byte other than kVersion
  WrongKey,        // minted with another key (its key id is not this key's)
  Tampered,        // the seal does not match its bytes: a byte was changed
  Expired,         // now >= expires_at
  WrongRoom,       // names a room other than this server's
};

// The text an Error gives for `problem` (each one different).
std::string describe(Problem problem);

struct Checked {
  Problem problem = Problem::None;
  Ticket ticket;  // the ticket's fields when problem is None
};

// Checks `text` against `key` at `now` (unix seconds, read by the caller) for a
// server whose room is `room`. The seal is checked in constant time, before any field
// is trusted.
Checked check(std::string_view text, const Key& key, std::uint64_t now, std::string_view room);

// The ticket's text, sealed with `key`. Throws std::invalid_argument for a room over
// kMaxRoomBytes.
std::string mint(const Ticket& ticket, const Key& key);

KeyId key_id(const Key& key);
// Random bytes from the system's generator.
Key new_key();
Nonce new_nonce();

}  // namespace ticket
