#pragma once
// physics-client --predict without --bots: a PredictingClient steering its body,
// one line per snapshot taken (the predicted and confirmed ticks, the own body as
// shown, the rollbacks so far).
#include <chrono>
#include <cstdint>

#include "client/game_message_plan.h"
#include "client/predicting_client.h"
#include "pattern.h"

namespace client_app {

struct PredictingRun {
  client::PredictingClientConfig config;
  AccelerationPattern pattern;
  client::GameMessagePlan messages;  // sent before the inputs; those received printed
  std::uint64_t ticks = 0;           // snapshots to print; 0: until the session ends
  bool json = false;
  std::chrono::milliseconds connect_timeout{5000};
};

// The exit code: 0 done, 1 could not connect (or the world did not parse), 3 the
// session or the prediction ended early.
int run_predicting(const PredictingRun& run);

}  // namespace client_app
