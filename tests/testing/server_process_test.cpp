// physics-server as a child process: the port from its listening line, clients over
// it, a clean stop on SIGTERM; and every way a start can fail, each with its message.
#include "physics_testing/server_process.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "physics_testing/clients.h"
#include "physics_testing/in_process_server.h"
#include "physics_testing/lockstep_check.h"

namespace physics_testing {
namespace {

using namespace std::chrono_literals;

ProcessOptions server_options() {
  ProcessOptions options;
  options.executable = PHYSICS_SERVER_EXE;
  return options;
}

// A shell script standing in for the server, to reach the failure paths.
class FakeServer {
 public:
  explicit FakeServer(const std::string& body)
      : path_(std::filesystem::temp_directory_path() /
              ("physics-testing-fake-" +
               std::to_string(::testing::UnitTest::GetInstance()->current_test_info()->line()) +
               ".sh")) {
    std::ofstream(path_) << "#!/bin/sh\n" << body << "\n";
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all);
  }
  ~FakeServer() { std::filesystem::remove(path_); }
  ProcessOptions options(std::chrono::milliseconds timeout = 5s) const {
    ProcessOptions options;
    options.executable = path_;
    options.start_timeout = timeout;
    return options;
  }

 private:
  std::filesystem::path path_;
};

std::string start_failure(ProcessOptions options) {
  try {
    ServerProcess process(std::move(options));
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "(it started)";
}

TEST(ServerProcess, ServesClientsOnThePortItPrintedAndStopsCleanly) {
  ServerProcess process(server_options());
  EXPECT_NE(process.port(), 0);
  EXPECT_TRUE(process.running());
  client::Client player(process.client_config("child-client"));
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string() << "\n" << process.log();
  ASSERT_TRUE(player.send_input(player.welcome().current_tick + 1, 0.0, 20.0));
  EXPECT_TRUE(wait_for_snapshot(
      player, [](const client::Snapshot& s) { return s.own && s.own->velocity.y > 0.0; }, 3s,
      "the own body rising"));
  EXPECT_EQ(process.stop(), 0) << process.log();
  EXPECT_FALSE(process.running());
  EXPECT_EQ(process.stop(), 0);  // idempotent
}

TEST(ServerProcess, ALockstepChildComputesTheSceneFilesWorld) {
  ProcessOptions options = server_options();
  options.scene_file = PHYSICS_SCENES_DIR "/circle-pile.textproto";
  options.extra_args = {"--lockstep", "--lockstep-pace", "asap", "--lockstep-timeout-ms", "10000"};
  ServerProcess process(options);
  Expected<scene::SceneDef> scene = load_scene(*options.scene_file);
  ASSERT_TRUE(scene);
  Expected<Clients> players = connect_clients(process.exact_client_config("p"), 2);
  ASSERT_TRUE(players) << process.log();
  EXPECT_TRUE((*players)[0]->welcome().lockstep);
  const auto script = [](std::size_t k, std::uint64_t t) {
    return client::Vec2{k == 0 ? 3.0 : -3.0, static_cast<double>(t % 5)};
  };
  EXPECT_TRUE(compare_lockstep_run(*scene, *players, script, 30));
}

TEST(ServerProcess, PassesTheTokenToItsClients) {
  ProcessOptions options = server_options();
  options.extra_args = {"--token", "s3cret"};
  ServerProcess process(options);
  EXPECT_EQ(process.endpoint().token, "s3cret");
  client::Client player(process.client_config());
  EXPECT_TRUE(player.connect(3s)) << player.last_error().to_string();
}

TEST(ServerProcess, AMissingExecutableCannotStart) {
  ProcessOptions options;
  options.executable = "/nonexistent/physics-server";
  const std::string message = start_failure(options);
  EXPECT_NE(message.find("cannot start /nonexistent/physics-server"), std::string::npos) << message;
}

TEST(ServerProcess, AServerThatRefusesItsFlagsReportsItsStatusAndLog) {
  ProcessOptions options = server_options();
  options.extra_args = {"--tick-rate", "abc"};
  const std::string message = start_failure(options);
  EXPECT_NE(message.find("exited with code"), std::string::npos) << message;
  EXPECT_NE(message.find("before listening"), std::string::npos) << message;
  EXPECT_NE(message.find("--tick-rate"), std::string::npos) << message;  // from its log
}

TEST(ServerProcess, AChildThatExitsFirstReportsItsExitCode) {
  FakeServer fake("echo 'starting up'; echo 'no port for you' >&2; exit 3");
  const std::string message = start_failure(fake.options());
  EXPECT_NE(message.find("exited with code 3 before listening"), std::string::npos) << message;
  EXPECT_NE(message.find("no port for you"), std::string::npos) << message;
}

TEST(ServerProcess, AChildThatNeverListensIsKilledAfterTheTimeout) {
  FakeServer fake("echo 'thinking'; exec sleep 30");
  const std::string message = start_failure(fake.options(200ms));
  EXPECT_NE(message.find("printed no 'listening on ADDRESS:PORT' line within 200 ms"),
            std::string::npos)
      << message;
}

TEST(ServerProcess, ReadsTheLineAmongOthersAndReportsASignalExit) {
  FakeServer fake("echo 'hello'; echo 'listening on 127.0.0.1:4242'; exec sleep 30");
  ServerProcess process(fake.options());
  EXPECT_EQ(process.port(), 4242);
  EXPECT_EQ(process.endpoint().host, "127.0.0.1");
  EXPECT_EQ(process.stop(), 128 + 15);  // sleep ended by SIGTERM
}

}  // namespace
}  // namespace physics_testing
