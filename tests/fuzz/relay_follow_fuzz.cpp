// libFuzzer harness: the relay follower (relay_follow_target.h), relay::follow and the
// predicting client's PredictionCore fed the RelayTicks of a hostile server.
#include <google/protobuf/stubs/logging.h>

#include <cstddef>
#include <cstdint>

#include "relay_follow_target.h"

// libprotobuf logs a line for every string field that is not UTF-8; a fuzzer makes
// millions of those.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  google::protobuf::SetLogHandler(nullptr);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  relay_fuzz::run_one(data, size);
  return 0;
}
