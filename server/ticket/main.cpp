// physics-ticket: writes a new ticket key file, or mints a connect ticket with one
// (docs/SERVER.md, "Connect tickets"). The ticket is printed on one line; a client
// sends it as Hello.access_token.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>

#include "ticket/key_file.h"
#include "ticket/ticket.h"

namespace {

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

struct Flags {
  std::string new_key;
  std::string key_file;
  std::optional<std::uint64_t> player_id;
  std::optional<std::uint32_t> seat;
  std::string room;
  std::uint64_t expires_in = 3600;
};

std::uint64_t unix_now() {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::seconds>(
                                        std::chrono::system_clock::now().time_since_epoch())
                                        .count());
}

int mint(const Flags& flags) {
  ticket::Key key{};
  if (const std::string error = ticket::read_key_file(flags.key_file, key); !error.empty()) {
    std::cerr << "physics-ticket: " << error << "\n";
    return kExitFailure;
  }
  ticket::Ticket t;
  t.player_id = *flags.player_id;
  t.seat = flags.seat;
  t.room = flags.room;
  t.expires_at = unix_now() + flags.expires_in;
  t.nonce = ticket::new_nonce();
  std::cout << ticket::mint(t, key) << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "physics-ticket: connect tickets for physics-server --ticket-key-file.\n"
      "  physics-ticket --new-key FILE      writes a new key (mode 0600; never overwrites)\n"
      "  physics-ticket --key-file FILE --player-id N [--seat S] [--room NAME] "
      "[--expires-in SECONDS]\n"
      "                                     prints a ticket for player N"};
  Flags flags;
  auto* new_key = app.add_option("--new-key", flags.new_key,
                                 "Write a new random key to this file, which must not exist");
  auto* key_file =
      app.add_option("--key-file", flags.key_file, "Mint a ticket with the key in this file")
          ->check(CLI::ExistingFile)
          ->excludes(new_key);
  auto* player = app.add_option("--player-id", flags.player_id,
                                "The player the ticket admits (a 64-bit id of your backend's)");
  auto* seat =
      app.add_option("--seat", flags.seat, "The seat held for the player in a lockstep lobby");
  auto* room = app.add_option("--room", flags.room,
                              "The room (server's scene name or --ticket-room) it is valid "
                              "in, at most 64 bytes; default: any room");
  auto* expires =
      app.add_option("--expires-in", flags.expires_in, "Seconds from now until it expires")
          ->capture_default_str()
          ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{10} * 365 * 24 * 3600));
  for (CLI::Option* option : {player, seat, room, expires}) option->needs(key_file);
  key_file->needs(player);
  try {
    app.parse(argc, argv);
    if (flags.new_key.empty() && flags.key_file.empty()) {
      throw CLI::RequiredError("--new-key or --key-file");
    }
    if (flags.room.size() > ticket::kMaxRoomBytes) {
      throw CLI::ValidationError("--room", "at most 64 bytes");
    }
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  }
  if (!flags.new_key.empty()) {
    if (const std::string error = ticket::write_key_file(flags.new_key, ticket::new_key());
        !error.empty()) {
      std::cerr << "physics-ticket: " << error << "\n";
      return kExitFailure;
    }
    return 0;
  }
  return mint(flags);
}
