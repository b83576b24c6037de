// physics-ticket and physics-server's ticket flags as a user runs them: --new-key
// writes an owner-only key once, a minted ticket carries the flags' fields and checks
// with the library, and physics-server refuses a ticket key given with a token.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "ticket/key_file.h"
#include "ticket/ticket.h"

namespace {

struct CommandRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

CommandRun run(const std::string& command) {
  CommandRun result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) {
    result.output += buffer.data();
  }
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string temp_dir() {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("physics-ticket-tool-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

std::uint64_t unix_now() {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::seconds>(
                                        std::chrono::system_clock::now().time_since_epoch())
                                        .count());
}

TEST(TicketTool, ANewKeyIsOwnerOnlyAndNeverOverwritten) {
  const std::string dir = temp_dir();
  const std::string key_file = dir + "/ticket.key";
  const std::string tool = PHYSICS_TICKET_TOOL;
  const CommandRun made = run(tool + " --new-key " + key_file);
  ASSERT_EQ(made.exit_code, 0) << made.output;
  struct stat info {};
  ASSERT_EQ(::stat(key_file.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0600u);
  ticket::Key key{};
  ASSERT_EQ(ticket::read_key_file(key_file, key), "");
  const CommandRun again = run(tool + " --new-key " + key_file);
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.output.find("never overwritten"), std::string::npos) << again.output;
  ticket::Key still{};
  ASSERT_EQ(ticket::read_key_file(key_file, still), "");
  EXPECT_EQ(still, key);
  std::filesystem::remove_all(dir);
}

TEST(TicketTool, AMintedTicketCarriesTheFlagsFields) {
  const std::string dir = temp_dir();
  const std::string key_file = dir + "/ticket.key";
  const std::string tool = PHYSICS_TICKET_TOOL;
  ASSERT_EQ(run(tool + " --new-key " + key_file).exit_code, 0);
  ticket::Key key{};
  ASSERT_EQ(ticket::read_key_file(key_file, key), "");
  const std::uint64_t before = unix_now();
  const CommandRun minted =
      run(tool + " --key-file " + key_file +
          " --player-id 18446744073709551615 --seat 3 --room arena --expires-in 600");
  ASSERT_EQ(minted.exit_code, 0) << minted.output;
  const std::string text = minted.output.substr(0, minted.output.find('\n'));
  const ticket::Checked checked = ticket::check(text, key, before, "arena");
  ASSERT_EQ(checked.problem, ticket::Problem::None) << ticket::describe(checked.problem);
  EXPECT_EQ(checked.ticket.player_id, 18446744073709551615u);
  EXPECT_EQ(checked.ticket.seat, std::optional<std::uint32_t>(3));
  EXPECT_GE(checked.ticket.expires_at, before + 600);
  EXPECT_LE(checked.ticket.expires_at, unix_now() + 600);
  EXPECT_EQ(ticket::check(text, key, before + 601 + (unix_now() - before), "arena").problem,
            ticket::Problem::Expired);
  // Without --player-id, or with a room over 64 bytes: a usage error.
  EXPECT_EQ(run(tool + " --key-file " + key_file).exit_code, 2);
  EXPECT_EQ(run(tool + " --key-file " + key_file + " --player-id 1 --room " + std::string(65, 'r'))
                .exit_code,
            2);
  std::filesystem::remove_all(dir);
}

TEST(TicketTool, TheServerRefusesATicketKeyWithAToken) {
  const std::string dir = temp_dir();
  const std::string key_file = dir + "/ticket.key";
  ASSERT_EQ(run(std::string(PHYSICS_TICKET_TOOL) + " --new-key " + key_file).exit_code, 0);
  const std::string server = PHYSICS_SERVER;
  const CommandRun both =
      run(server + " --port 0 --ticket-key-file " + key_file + " --token sesame");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.output.find("--ticket-key-file replaces the access token"), std::string::npos)
      << both.output;
  const CommandRun from_env =
      run("PHYSICS_TOKEN=sesame " + server + " --port 0 --ticket-key-file " + key_file);
  EXPECT_EQ(from_env.exit_code, 2) << from_env.output;
  const CommandRun room_alone = run(server + " --port 0 --ticket-room arena");
  EXPECT_EQ(room_alone.exit_code, 2);
  EXPECT_NE(room_alone.output.find("--ticket-room needs --ticket-key-file"), std::string::npos)
      << room_alone.output;
  std::filesystem::remove_all(dir);
}

}  // namespace
