// The recording container: what the writer writes, the reader reads back, record
// by record with each one's offset.
#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include <variant>

#include "replay_support.h"

namespace {

physics::recording::Record input(std::uint64_t tick, double ax) {
  physics::recording::Record record;
  record.mutable_input()->set_tick(tick);
  record.mutable_input()->set_client(4);
  record.mutable_input()->set_ax(ax);
  return record;
}

TEST(RecordingFile, WhatIsWrittenIsReadBackWithItsOffsets) {
  rtest::TempFile file("roundtrip.rec");
  physics::recording::Header header;
  header.mutable_client()->set_name("n");
  header.mutable_client()->set_port(7777);
  std::string error;
  {
    auto writer = recording::RecordingWriter::create(file.path(), header, &error);
    ASSERT_TRUE(writer) << error;
    for (std::uint64_t t = 1; t <= 300; ++t)
      ASSERT_TRUE(writer->append(input(t, 0.25 * static_cast<double>(t))));
  }
  const std::string bytes = file.bytes();
  ASSERT_EQ(bytes.substr(0, 8), std::string("PHYSREC\n"));
  EXPECT_EQ(bytes.substr(8, 4), std::string("\x01\x00\x00\x00", 4));

  const recording::LoadedRecording loaded = rtest::load_or_fail(file.path());
  EXPECT_TRUE(google::protobuf::util::MessageDifferencer::Equals(loaded.header, header));
  ASSERT_EQ(loaded.records.size(), 300u);
  ASSERT_EQ(loaded.offsets.size(), 300u);
  std::uint64_t offset = recording::kPreambleBytes + 1 + header.ByteSizeLong();
  EXPECT_EQ(loaded.header_offset, recording::kPreambleBytes + 1);
  for (std::size_t i = 0; i < loaded.records.size(); ++i) {
    EXPECT_TRUE(google::protobuf::util::MessageDifferencer::Equals(
        loaded.records[i], input(i + 1, 0.25 * static_cast<double>(i + 1))));
    EXPECT_EQ(loaded.offsets[i], offset);
    offset += 1 + loaded.records[i].ByteSizeLong();
  }
  EXPECT_EQ(offset, bytes.size());
  // The same bytes in memory read the same.
  EXPECT_EQ(recording::encode_recording(loaded.header, loaded.records), bytes);
}

TEST(RecordingFile, AFileThatCannotBeCreatedSaysWhy) {
  physics::recording::Header header;
  header.mutable_client();
  std::string error;
  EXPECT_EQ(recording::RecordingWriter::create("/nonexistent/dir/x.rec", header, &error), nullptr);
  EXPECT_NE(error.find("cannot create /nonexistent/dir/x.rec"), std::string::npos) << error;
}

}  // namespace
