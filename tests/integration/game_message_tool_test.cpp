// physics-client's game messages against a real server with rules: --game-message
// reaches the rules once (or on its schedule with --message-every-ms), the rules'
// replies are printed (text, or base64 when they are not UTF-8), and --bots counts
// the messages its bots sent and received.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "harness.h"
#include "server/game_rules.h"

namespace itest {
namespace {

struct Delivered {
  server::ClientId client = 0;
  std::uint64_t tick = 0;
  std::string payload;
};

// Answers each message to its sender: "got <payload>" stamped with the tick it was
// delivered at, and to "bytes" also three bytes that are not UTF-8.
class EchoRules : public server::GameRules {
 public:
  void before_step(server::GameWorld& w, const std::vector<server::AppliedInput>&) override {
    for (const server::ClientGameMessage& m : w.messages()) {
      {
        const std::lock_guard lock(mutex_);
        delivered_.push_back({m.client, w.tick(), m.payload});
      }
      w.send(m.client, "got " + m.payload);
      if (m.payload == "bytes") w.send(m.client, std::string("\xff\x00\x01", 3));
    }
  }
  std::vector<Delivered> delivered() const {
    const std::lock_guard lock(mutex_);
    return delivered_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<Delivered> delivered_;
};

struct CommandRun {
  int exit_code = -1;
  std::vector<std::string> lines;
};

// physics-client with `flags` against `server` (stderr merged), its lines and exit code.
CommandRun run_client(const RunningServer& server, const std::string& flags) {
  const std::string command = std::string(PHYSICS_CLIENT_EXE) + " --port " +
                              std::to_string(server.port()) + " " + flags + " 2>&1";
  CommandRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  std::string line;
  for (int c = std::fgetc(pipe); c != EOF; c = std::fgetc(pipe)) {
    if (c == '\n') {
      run.lines.push_back(line);
      line.clear();
    } else {
      line.push_back(static_cast<char>(c));
    }
  }
  if (!line.empty()) run.lines.push_back(line);
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

std::vector<std::string> starting_with(const CommandRun& run, const std::string& prefix) {
  std::vector<std::string> found;
  for (const auto& line : run.lines) {
    if (line.rfind(prefix, 0) == 0) found.push_back(line);
  }
  return found;
}

std::string all_lines(const CommandRun& run) {
  std::string all;
  for (const auto& line : run.lines) all += line + "\n";
  return all;
}

TEST(GameMessageTool, ReachesTheRulesOnceAndPrintsTheirReplies) {
  server::ServerConfig config = test_config(/*lockstep=*/true);
  auto rules = std::make_shared<EchoRules>();
  config.rules = rules;
  RunningServer server(config, scene::default_scene());
  const CommandRun run =
      run_client(server, "--ticks 30 --json --game-message jump --game-message bytes");
  ASSERT_EQ(run.exit_code, 0) << all_lines(run);

  // Sent once, both payloads at the same tick, in the order given.
  const std::vector<Delivered> delivered = rules->delivered();
  ASSERT_EQ(delivered.size(), 2u) << all_lines(run);
  EXPECT_EQ(delivered[0].payload, "jump");
  EXPECT_EQ(delivered[1].payload, "bytes");
  EXPECT_EQ(delivered[0].tick, delivered[1].tick);
  EXPECT_EQ(delivered[0].client, delivered[1].client);

  // The replies, each a JSON line stamped with the tick the rules sent it in.
  const std::string tick = std::to_string(delivered[0].tick);
  const std::vector<std::string> replies = starting_with(run, "{\"game_message\":");
  ASSERT_EQ(replies.size(), 3u) << all_lines(run);
  EXPECT_EQ(replies[0], "{\"game_message\":{\"tick\":" + tick + ",\"text\":\"got jump\"}}");
  EXPECT_EQ(replies[1], "{\"game_message\":{\"tick\":" + tick + ",\"text\":\"got bytes\"}}");
  EXPECT_EQ(replies[2], "{\"game_message\":{\"tick\":" + tick + ",\"base64\":\"/wAB\"}}");
}

TEST(GameMessageTool, TextLinesNameTheTickAndSayWhenThePayloadIsBase64) {
  server::ServerConfig config = test_config(/*lockstep=*/true);
  auto rules = std::make_shared<EchoRules>();
  config.rules = rules;
  RunningServer server(config, scene::default_scene());
  const CommandRun run = run_client(server, "--ticks 30 --game-message bytes");
  ASSERT_EQ(run.exit_code, 0) << all_lines(run);
  ASSERT_EQ(rules->delivered().size(), 1u);
  const std::string tick = std::to_string(rules->delivered()[0].tick);
  const std::vector<std::string> replies = starting_with(run, "game message ");
  ASSERT_EQ(replies.size(), 2u) << all_lines(run);
  EXPECT_EQ(replies[0], "game message tick " + tick + ": got bytes");
  EXPECT_EQ(replies[1], "game message tick " + tick + " (base64): /wAB");
}

// --message-every-ms sends the payload again on its schedule (the schedule itself is
// tests/client's, on a made-up clock): at 1 ms on a server stepping every 16.7 ms,
// a round goes before nearly every input, and each is answered at its tick.
TEST(GameMessageTool, MessageEveryMsSendsAgainEachAtItsOwnTick) {
  server::ServerConfig config = test_config();
  auto rules = std::make_shared<EchoRules>();
  config.rules = rules;
  RunningServer server(config, scene::default_scene());
  const CommandRun run =
      run_client(server, "--ticks 40 --json --game-message dash --message-every-ms 1");
  ASSERT_EQ(run.exit_code, 0) << all_lines(run);
  const std::vector<Delivered> delivered = rules->delivered();
  ASSERT_GE(delivered.size(), 10u) << all_lines(run);
  EXPECT_GT(delivered.back().tick, delivered.front().tick + 5);
  for (std::size_t i = 1; i < delivered.size(); ++i) {
    EXPECT_EQ(delivered[i].payload, "dash");
    // At a fixed rate a message for a tick already stepped is delivered at the next
    // one, with the next round's: ticks never go back.
    EXPECT_GE(delivered[i].tick, delivered[i - 1].tick);
  }
  // Every reply printed is one of them, at its tick; those sent after the client's
  // last snapshot are not printed.
  const std::vector<std::string> replies = starting_with(run, "{\"game_message\":");
  ASSERT_GE(replies.size(), 5u);
  ASSERT_LE(replies.size(), delivered.size());
  for (std::size_t i = 0; i < replies.size(); ++i) {
    EXPECT_EQ(replies[i], "{\"game_message\":{\"tick\":" + std::to_string(delivered[i].tick) +
                              ",\"text\":\"got dash\"}}");
  }
}

TEST(GameMessageTool, BotsCountTheMessagesTheySentAndReceived) {
  server::ServerConfig config = test_config();
  auto rules = std::make_shared<EchoRules>();
  config.rules = rules;
  RunningServer server(config, scene::default_scene());
  const CommandRun run = run_client(server, "--bots 2 --duration 0.5 --json --game-message shoot");
  ASSERT_EQ(run.exit_code, 0) << all_lines(run);
  ASSERT_FALSE(run.lines.empty());
  const std::string& report = run.lines.back();
  EXPECT_NE(report.find("\"game_messages_sent\":2,"), std::string::npos) << report;
  EXPECT_NE(report.find("\"game_messages_received\":2,"), std::string::npos) << report;
  const std::vector<Delivered> delivered = rules->delivered();
  ASSERT_EQ(delivered.size(), 2u);
  EXPECT_NE(delivered[0].client, delivered[1].client);
}

}  // namespace
}  // namespace itest
