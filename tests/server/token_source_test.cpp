// Where the access token comes from: the flag, a file, or PHYSICS_TOKEN.
#include "server/token_source.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace {

using server::choose_token;
using server::TokenSources;

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(TokenSource, NothingGivenMeansNoToken) {
  const auto choice = choose_token({});
  EXPECT_TRUE(choice.error.empty());
  EXPECT_FALSE(choice.token.has_value());
}

TEST(TokenSource, TheFileGivesItsFirstLineWithoutTheLineEnd) {
  TokenSources sources;
  sources.file = write_temp("token-crlf", "s3cret\r\nsecond line\n");
  const auto choice = choose_token(sources);
  ASSERT_TRUE(choice.error.empty()) << choice.error;
  EXPECT_EQ(choice.token, "s3cret");
}

TEST(TokenSource, FlagOrFileWinOverTheEnvironment) {
  TokenSources sources;
  sources.env = "from-env";
  EXPECT_EQ(choose_token(sources).token, "from-env");
  sources.file = write_temp("token-file", "from-file\n");
  EXPECT_EQ(choose_token(sources).token, "from-file");
  sources.file.clear();
  sources.flag = "from-flag";
  EXPECT_EQ(choose_token(sources).token, "from-flag");
}

TEST(TokenSource, BadSourcesAreErrorsNotAnOpenServer) {
  TokenSources both;
  both.flag = "a";
  both.file = write_temp("token-both", "b\n");
  EXPECT_FALSE(choose_token(both).error.empty());
  TokenSources missing;
  missing.file = ::testing::TempDir() + "no-such-token-file";
  EXPECT_FALSE(choose_token(missing).error.empty());
  TokenSources empty_file;
  empty_file.file = write_temp("token-empty", "\n");
  EXPECT_FALSE(choose_token(empty_file).error.empty());
  TokenSources empty_env;
  empty_env.env = "";
  EXPECT_FALSE(choose_token(empty_env).error.empty());
}

}  // namespace
