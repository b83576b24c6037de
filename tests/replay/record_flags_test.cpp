// The command lines: physics-server --record and physics-client --record as
// processes, the server's recording checked by physics-sim's replayer.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "physics_testing/server_process.h"
#include "replay_support.h"
#include "replayer.h"
#include "wire.pb.h"

namespace {

TEST(RecordFlags, ServerAndClientRecordingsOfProcessesReplayAndRead) {
  rtest::TempFile server_file("server.rec");
  rtest::TempFile client_file("client.rec");
  {
    physics_testing::ProcessOptions options;
    options.executable = PHYSICS_SERVER_EXE;
    options.extra_args = {"--record", server_file.path().string()};
    physics_testing::ServerProcess server(options);
    const std::string command =
        std::string(PHYSICS_CLIENT_EXE) + " --port " + std::to_string(server.port()) +
        " --ticks 40 --accel 3,1 --record " + client_file.path().string() + " > /dev/null";
    ASSERT_EQ(std::system(command.c_str()), 0);
    EXPECT_EQ(server.stop(), 0) << server.log();
  }
  const replay::ReplayReport report = replay::check_recording_file(server_file.path());
  EXPECT_EQ(report.outcome, replay::ReplayReport::Outcome::Equal) << report.error.to_string();
  EXPECT_GE(report.ticks, 40u);
  EXPECT_EQ(report.hashes_checked, report.ticks);
  const recording::LoadedRecording server_run = rtest::load_or_fail(server_file.path());
  EXPECT_EQ(rtest::count_kind(server_run, physics::recording::Record::kJoin), 1u);
  EXPECT_EQ(rtest::count_kind(server_run, physics::recording::Record::kLeave), 1u);
  // A constant input: written once.
  EXPECT_EQ(rtest::count_kind(server_run, physics::recording::Record::kInput), 1u);

  const recording::LoadedRecording client_run = rtest::load_or_fail(client_file.path());
  ASSERT_TRUE(client_run.header.has_client());
  ASSERT_GE(client_run.records.size(), 41u);  // the Welcome and 40 snapshots at least
  physics::wire::ServerMessage first;
  ASSERT_TRUE(first.ParseFromString(client_run.records.front().received().server_message()));
  EXPECT_TRUE(first.has_welcome());
}

}  // namespace
