// Connect tickets: the worked example of docs/PROTOCOL.md ("Connect tickets") to the
// byte, a valid ticket's fields, and each refusal with its own reason: missing,
// malformed, another version, another key, any byte changed, expired, another room.
#include "ticket/ticket.h"

#include <gtest/gtest.h>
#include <sodium.h>

#include <set>
#include <string>
#include <vector>

namespace {

using ticket::Problem;

ticket::Key example_key() {
  ticket::Key key{};
  for (std::size_t i = 0; i < key.size(); ++i) key[i] = static_cast<std::uint8_t>(i);
  return key;
}

ticket::Ticket example_ticket() {
  ticket::Ticket t;
  t.player_id = 42;
  t.seat = 1;
  t.room = "goal-rush";
  t.expires_at = 1767225600;  // 2026-01-01T00:00:00Z
  for (std::size_t i = 0; i < t.nonce.size(); ++i) t.nonce[i] = static_cast<std::uint8_t>(0xa0 + i);
  return t;
}

// docs/PROTOCOL.md's worked example, and the bytes under it.
constexpr const char* kExampleTicket =
    "AQH0DmZPKgAAAAAAAAABAAAAALlVaQAAAACgoaKjpKWmp6ipqqusra6vCWdvYWwtcnVzaAqJWqRuKs6LuSanEdm5ZyJTEb"
    "ZwumTzj-CUcxFM98z3";

constexpr std::uint64_t kBefore = 1767225599;  // one second before it expires

std::vector<std::uint8_t> decode(const std::string& text) {
  std::vector<std::uint8_t> bytes(text.size());
  std::size_t size = 0;
  EXPECT_EQ(sodium_base642bin(bytes.data(), bytes.size(), text.data(), text.size(), nullptr, &size,
                              nullptr, sodium_base64_VARIANT_URLSAFE_NO_PADDING),
            0);
  bytes.resize(size);
  return bytes;
}

std::string encode(const std::vector<std::uint8_t>& bytes) {
  std::string text(
      sodium_base64_ENCODED_LEN(bytes.size(), sodium_base64_VARIANT_URLSAFE_NO_PADDING), '\0');
  sodium_bin2base64(text.data(), text.size(), bytes.data(), bytes.size(),
                    sodium_base64_VARIANT_URLSAFE_NO_PADDING);
  text.resize(text.find('\0'));
  return text;
}

TEST(Ticket, TheWorkedExampleIsExactlyThePagesString) {
  EXPECT_EQ(ticket::mint(example_ticket(), example_key()), kExampleTicket);
  const std::vector<std::uint8_t> bytes = decode(kExampleTicket);
  ASSERT_EQ(bytes.size(), ticket::kFixedBytes + 9);
  // The page's first bytes: version 1, a seat, the key id f4 0e 66 4f, player 42.
  const std::vector<std::uint8_t> head = {0x01, 0x01, 0xf4, 0x0e, 0x66, 0x4f, 0x2a};
  EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 7), head);
  const ticket::KeyId id = ticket::key_id(example_key());
  EXPECT_EQ(std::vector<std::uint8_t>(id.begin(), id.end()),
            std::vector<std::uint8_t>(head.begin() + 2, head.begin() + 6));
}

TEST(Ticket, AValidTicketGivesBackItsFields) {
  const ticket::Checked checked =
      ticket::check(kExampleTicket, example_key(), kBefore, "goal-rush");
  ASSERT_EQ(checked.problem, Problem::None) << ticket::describe(checked.problem);
  EXPECT_EQ(checked.ticket.player_id, 42u);
  EXPECT_EQ(checked.ticket.seat, std::optional<std::uint32_t>(1));
  EXPECT_EQ(checked.ticket.room, "goal-rush");
  EXPECT_EQ(checked.ticket.expires_at, 1767225600u);
  EXPECT_EQ(checked.ticket.nonce, example_ticket().nonce);
}

TEST(Ticket, WithoutASeatOrARoomItIsValidInAnyRoomAndHasNoSeat) {
  ticket::Ticket t = example_ticket();
  t.seat.reset();
  t.room.clear();
  t.player_id = 0xfedcba9876543210u;
  const std::string text = ticket::mint(t, example_key());
  EXPECT_EQ(text.size(), 100u);
  const ticket::Checked checked = ticket::check(text, example_key(), kBefore, "any-room");
  ASSERT_EQ(checked.problem, Problem::None) << ticket::describe(checked.problem);
  EXPECT_EQ(checked.ticket.player_id, 0xfedcba9876543210u);
  EXPECT_FALSE(checked.ticket.seat.has_value());
}

TEST(Ticket, ExpiresAtItsSecond) {
  EXPECT_EQ(ticket::check(kExampleTicket, example_key(), 1767225600, "goal-rush").problem,
            Problem::Expired);
  EXPECT_EQ(ticket::check(kExampleTicket, example_key(), 1767225600 + 3600, "goal-rush").problem,
            Problem::Expired);
}

TEST(Ticket, AnotherRoomIsRefused) {
  EXPECT_EQ(ticket::check(kExampleTicket, example_key(), kBefore, "goal-rush-2").problem,
            Problem::WrongRoom);
  EXPECT_EQ(ticket::check(kExampleTicket, example_key(), kBefore, "").problem, Problem::WrongRoom);
}

TEST(Ticket, AnotherKeyIsRefusedAsAnotherKey) {
  ticket::Key other = example_key();
  other[31] ^= 0x01;
  EXPECT_EQ(ticket::check(kExampleTicket, other, kBefore, "goal-rush").problem, Problem::WrongKey);
  EXPECT_EQ(ticket::check(ticket::mint(example_ticket(), ticket::new_key()), example_key(), kBefore,
                          "goal-rush")
                .problem,
            Problem::WrongKey);
}

// Every bit of every byte matters: a change anywhere is refused, and a change to a
// field the seal covers is reported as tampering.
TEST(Ticket, EveryByteFlippedIsRefused) {
  const std::vector<std::uint8_t> bytes = decode(kExampleTicket);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    for (const int flip : {0x01, 0x80, 0xff}) {
      std::vector<std::uint8_t> changed = bytes;
      changed[i] ^= static_cast<std::uint8_t>(flip);
      const Problem problem =
          ticket::check(encode(changed), example_key(), kBefore, "goal-rush").problem;
      EXPECT_NE(problem, Problem::None) << "byte " << i << " ^ " << flip;
      const bool field = i >= 6 && i != 42;  // past the key id; not the room's length
      if (field) {
        EXPECT_EQ(problem, Problem::Tampered) << "byte " << i << " ^ " << flip;
      }
    }
  }
  std::vector<std::uint8_t> version = bytes;
  version[0] = 2;
  EXPECT_EQ(ticket::check(encode(version), example_key(), kBefore, "goal-rush").problem,
            Problem::UnknownVersion);
}

TEST(Ticket, MissingAndMalformedTicketsAreRefused) {
  EXPECT_EQ(ticket::check("", example_key(), kBefore, "goal-rush").problem, Problem::Missing);
  const std::string text = kExampleTicket;
  for (const std::string& bad : {std::string("sesame"), text + "=", text.substr(0, text.size() - 1),
                                 text + "AAAA", "+" + text.substr(1), std::string(4096, 'A')}) {
    EXPECT_EQ(ticket::check(bad, example_key(), kBefore, "goal-rush").problem, Problem::Malformed)
        << bad;
  }
}

TEST(Ticket, EachProblemHasItsOwnText) {
  std::set<std::string> texts;
  for (const Problem problem :
       {Problem::Missing, Problem::Malformed, Problem::UnknownVersion, Problem::WrongKey,
        Problem::Tampered, Problem::Expired, Problem::WrongRoom}) {
    EXPECT_TRUE(texts.insert(ticket::describe(problem)).second) << ticket::describe(problem);
  }
}

TEST(Ticket, NewNoncesAndKeysDifferAndTheLongestRoomFits) {
  EXPECT_NE(ticket::new_nonce(), ticket::new_nonce());
  EXPECT_NE(ticket::new_key(), ticket::new_key());
  ticket::Ticket t = example_ticket();
  t.room = std::string(ticket::kMaxRoomBytes, 'r');
  const std::string text = ticket::mint(t, example_key());
  EXPECT_EQ(text.size(), 186u);
  EXPECT_EQ(ticket::check(text, example_key(), kBefore, t.room).problem, Problem::None);
  t.room.push_back('r');
  EXPECT_THROW(ticket::mint(t, example_key()), std::invalid_argument);
}

}  // namespace
