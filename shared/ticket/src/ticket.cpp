#include "ticket/ticket.h"

#include <sodium.h>

#include <cstring>
#include <stdexcept>
#include <vector>

namespace ticket {
namespace {

constexpr std::uint8_t kHasSeat = 0x01;
constexpr std::string_view kKeyIdLabel = "physics ticket key id";
// Where each field starts in the sealed bytes.
constexpr std::size_t kFlagsAt = 1;
constexpr std::size_t kKeyIdAt = 2;
constexpr std::size_t kPlayerAt = kKeyIdAt + kKeyIdBytes;
constexpr std::size_t kSeatAt = kPlayerAt + 8;
constexpr std::size_t kExpiresAt = kSeatAt + 4;
constexpr std::size_t kNonceAt = kExpiresAt + 8;
constexpr std::size_t kRoomLengthAt = kNonceAt + kNonceBytes;
constexpr std::size_t kRoomAt = kRoomLengthAt + 1;

// sodium_init is idempotent and thread-safe; randombytes needs it first.
void ensure_sodium() {
  static const int ready = sodium_init();
  if (ready < 0) throw std::runtime_error("libsodium failed to initialise");
}

void put_le(std::vector<std::uint8_t>& out, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

std::uint64_t get_le(const std::uint8_t* at, int bytes) {
  std::uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) value |= std::uint64_t{at[i]} << (8 * i);
  return value;
}

using Mac = std::array<std::uint8_t, kMacBytes>;

Mac seal(const Key& key, const std::uint8_t* bytes, std::size_t size) {
  Mac mac{};
  crypto_auth_hmacsha256_state state;
  crypto_auth_hmacsha256_init(&state, key.data(), key.size());
  crypto_auth_hmacsha256_update(&state, bytes, size);
  crypto_auth_hmacsha256_final(&state, mac.data());
  return mac;
}

// base64url without padding -> bytes; nullopt for anything else (padding, spaces,
// stray bits in the last character).
std::optional<std::vector<std::uint8_t>> from_base64url(std::string_view text) {
  std::vector<std::uint8_t> bytes(text.size() * 3 / 4 + 1);
  std::size_t size = 0;
  const char* end = nullptr;
  if (sodium_base642bin(bytes.data(), bytes.size(), text.data(), text.size(), nullptr, &size, &end,
                        sodium_base64_VARIANT_URLSAFE_NO_PADDING) != 0 ||
      end != text.data() + text.size()) {
    return std::nullopt;
  }
  bytes.resize(size);
  return bytes;
}

}  // namespace

std::string describe(Problem problem) {
  switch (problem) {
    case Problem::None:
      return "a valid ticket";
    case Problem::Missing:
      return "this server admits connect tickets only: Hello.access_token is empty";
    case Problem::Malformed:
      return "Hello.access_token is not a connect ticket (not base64url, or the wrong length)";
    case Problem::UnknownVersion:
      return "the ticket's format version is not " + std::to_string(kVersion);
    case Problem::WrongKey:
      return "the ticket was minted with another key than this server's";
    case Problem::Tampered:
      return "the ticket's seal does not match its bytes: it was changed after minting";
    case Problem::Expired:
      return "the ticket has expired";
    case Problem::WrongRoom:
      return "the ticket is for another room";
  }
  return "unknown ticket problem";
}

KeyId key_id(const Key& key) {
  const Mac mac =
      seal(key, reinterpret_cast<const std::uint8_t*>(kKeyIdLabel.data()), kKeyIdLabel.size());
  KeyId id{};
  std::memcpy(id.data(), mac.data(), id.size());
  return id;
}

std::string mint(const Ticket& ticket, const Key& key) {
  if (ticket.room.size() > kMaxRoomBytes) {
    throw std::invalid_argument("a ticket's room is at most " + std::to_string(kMaxRoomBytes) +
                                " bytes");
  }
  std::vector<std::uint8_t> bytes;
  bytes.reserve(kFixedBytes + ticket.room.size());
  bytes.push_back(kVersion);
  bytes.push_back(ticket.seat ? kHasSeat : 0);
  const KeyId id = key_id(key);
  bytes.insert(bytes.end(), id.begin(), id.end());
  put_le(bytes, ticket.player_id, 8);
  put_le(bytes, ticket.seat.value_or(0), 4);
  put_le(bytes, ticket.expires_at, 8);
  bytes.insert(bytes.end(), ticket.nonce.begin(), ticket.nonce.end());
  bytes.push_back(static_cast<std::uint8_t>(ticket.room.size()));
  bytes.insert(bytes.end(), ticket.room.begin(), ticket.room.end());
  const Mac mac = seal(key, bytes.data(), bytes.size());
  bytes.insert(bytes.end(), mac.begin(), mac.end());
  std::string text(
      sodium_base64_ENCODED_LEN(bytes.size(), sodium_base64_VARIANT_URLSAFE_NO_PADDING), '\0');
  sodium_bin2base64(text.data(), text.size(), bytes.data(), bytes.size(),
                    sodium_base64_VARIANT_URLSAFE_NO_PADDING);
  text.resize(std::strlen(text.c_str()));
  return text;
}

Checked check(std::string_view text, const Key& key, std::uint64_t now, std::string_view room) {
  Checked checked;
  if (text.empty()) {
    checked.problem = Problem::Missing;
    return checked;
  }
  // Longer text cannot be a ticket: refused before it is decoded.
  const std::size_t max_text = (kFixedBytes + kMaxRoomBytes + 2) / 3 * 4;
  const auto decoded = text.size() <= max_text ? from_base64url(text) : std::nullopt;
  if (!decoded || decoded->size() < kFixedBytes ||
      decoded->size() != kFixedBytes + (*decoded)[kRoomLengthAt]) {
    checked.problem = Problem::Malformed;
    return checked;
  }
  const std::vector<std::uint8_t>& bytes = *decoded;
  if (bytes[0] != kVersion) {
    checked.problem = Problem::UnknownVersion;
    return checked;
  }
  const KeyId id = key_id(key);
  if (std::memcmp(bytes.data() + kKeyIdAt, id.data(), id.size()) != 0) {
    checked.problem = Problem::WrongKey;
    return checked;
  }
  const std::size_t sealed = bytes.size() - kMacBytes;
  const Mac mac = seal(key, bytes.data(), sealed);
  if (sodium_memcmp(mac.data(), bytes.data() + sealed, kMacBytes) != 0) {
    checked.problem = Problem::Tampered;
    return checked;
  }
  // Sealed by the key's holder from here on: the fields are as it wrote them.
  if ((bytes[kFlagsAt] & ~kHasSeat) != 0) {
    checked.problem = Problem::Malformed;
    return checked;
  }
  Ticket& t = checked.ticket;
  t.player_id = get_le(bytes.data() + kPlayerAt, 8);
  if ((bytes[kFlagsAt] & kHasSeat) != 0) {
    t.seat = static_cast<std::uint32_t>(get_le(bytes.data() + kSeatAt, 4));
  }
  t.expires_at = get_le(bytes.data() + kExpiresAt, 8);
  std::memcpy(t.nonce.data(), bytes.data() + kNonceAt, kNonceBytes);
  t.room.assign(reinterpret_cast<const char*>(bytes.data() + kRoomAt), bytes[kRoomLengthAt]);
  if (now >= t.expires_at) {
    checked.problem = Problem::Expired;
  } else if (!t.room.empty() && t.room != room) {
    checked.problem = Problem::WrongRoom;
  }
  return checked;
}

Key new_key() {
  ensure_sodium();
  Key key{};
  randombytes_buf(key.data(), key.size());
  return key;
}

Nonce new_nonce() {
  ensure_sodium();
  Nonce nonce{};
  randombytes_buf(nonce.data(), nonce.size());
  return nonce;
}

}  // namespace ticket
