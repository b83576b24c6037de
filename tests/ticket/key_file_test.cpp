// Ticket key files: written once with mode 0600 and never overwritten, read back as
// the same key; anything but 64 hexadecimal digits on the first line is refused.
#include "ticket/key_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace {

std::string temp_path(const std::string& name) {
  const std::string path =
      (std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()))).string();
  std::filesystem::remove(path);
  return path;
}

TEST(TicketKeyFile, WrittenOwnerOnlyReadBackAndNeverOverwritten) {
  const std::string path = temp_path("ticket-key");
  const ticket::Key key = ticket::new_key();
  ASSERT_EQ(ticket::write_key_file(path, key), "");
  struct stat info {};
  ASSERT_EQ(::stat(path.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0600u);
  ticket::Key read{};
  EXPECT_EQ(ticket::read_key_file(path, read), "");
  EXPECT_EQ(read, key);
  const std::string refused = ticket::write_key_file(path, ticket::new_key());
  EXPECT_NE(refused.find("never overwritten"), std::string::npos) << refused;
  EXPECT_EQ(ticket::read_key_file(path, read), "");
  EXPECT_EQ(read, key);
  std::filesystem::remove(path);
}

TEST(TicketKeyFile, OnlySixtyFourHexDigitsAreAKey) {
  ticket::Key key{};
  EXPECT_TRUE(ticket::key_from_hex(std::string(64, 'a'), key));
  EXPECT_EQ(key[0], 0xaa);
  EXPECT_FALSE(ticket::key_from_hex(std::string(63, 'a'), key));
  EXPECT_FALSE(ticket::key_from_hex(std::string(66, 'a'), key));
  EXPECT_FALSE(ticket::key_from_hex(std::string(63, 'a') + "g", key));
  const std::string path = temp_path("not-a-key");
  std::ofstream(path) << "sesame\n";
  EXPECT_NE(ticket::read_key_file(path, key), "");
  EXPECT_NE(ticket::read_key_file(path + "-missing", key), "");
  std::filesystem::remove(path);
}

}  // namespace
