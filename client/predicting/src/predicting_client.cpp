// A PredictingClient's session: the thin client's connection and input pacer,
// with the prediction core fed from what they take in.
#include "client/predicting_client.h"

#include <algorithm>
#include <utility>

namespace client {
namespace {

PredictingClientConfig with_world(PredictingClientConfig config) {
  config.client.want_world = true;
  config.client.view.encoding = Encoding::Inputs;
  config.client.run_rules = config.rules != nullptr;
  // The prediction is shown as soon as an input leaves, not at the next snapshot.
  config.pacer.return_after_send = true;
  return config;
}

}  // namespace

PredictingClient::PredictingClient(PredictingClientConfig config)
    : config_(with_world(std::move(config))),
      connection_(config_.client),
      core_(config_.prediction) {}

PredictingClient::~PredictingClient() = default;

bool PredictingClient::connect(std::chrono::milliseconds timeout) {
  pacer_.reset();
  last_snapshot_.reset();
  start_error_.clear();
  core_ = PredictionCore(config_.prediction);
  core_.set_rules(config_.rules);
  if (!connection_.connect(timeout)) return false;
  if (!core_.start(connection_.welcome())) {
    start_error_ = core_.error();
    connection_.disconnect("cannot run the world: " + start_error_);
    return false;
  }
  if (!connection_.welcome().spectator) {
    pacer_ = std::make_unique<InputPacer>(connection_, config_.pacer);
  }
  return true;
}

PollResult PredictingClient::poll(std::chrono::steady_clock::time_point deadline,
                                  const InputPacer::InputFor& input) {
  if (connection_.state() != ConnectionState::Connected || core_.failed()) return PollResult::Ended;
  std::optional<Snapshot> snapshot;
  std::uint64_t sent_before = 0;
  if (pacer_) {
    sent_before = pacer_->last_sent();
    const InputPacer::InputFor record = [&](std::uint64_t tick) {
      const Vec2 a = input(tick);
      core_.set_input(tick, a);
      return a;
    };
    snapshot = pacer_->poll(deadline, record);
  } else {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(
        std::max<std::chrono::steady_clock::duration>(deadline - std::chrono::steady_clock::now(),
                                                      std::chrono::steady_clock::duration::zero()));
    snapshot = connection_.next_snapshot(left);
  }
  const bool took = snapshot.has_value();
  if (took) {
    core_.on_snapshot(*snapshot);
    last_snapshot_ = std::move(snapshot);
  }
  if (core_.take_full_state_request()) {
    if (connection_.request_full_state()) ++requests_sent_;
  }
  if (pacer_) core_.advance_to(pacer_->last_sent());
  if (connection_.state() != ConnectionState::Connected || core_.failed()) return PollResult::Ended;
  if (took) return PollResult::Snapshot;
  if (pacer_ && pacer_->last_sent() != sent_before) return PollResult::InputSent;
  return PollResult::Deadline;
}

bool PredictingClient::send_game_message(std::uint64_t tick, const std::string& payload) {
  if (!connection_.send_game_message(tick, payload)) return false;
  core_.send_message(tick, payload);
  return true;
}

PredictingStats PredictingClient::stats() const {
  PredictingStats stats;
  stats.prediction = core_.stats();
  stats.bytes_received = connection_.stats().bytes_received;
  stats.snapshots = connection_.stats().snapshots_received;
  stats.full_state_requests_sent = requests_sent_;
  return stats;
}

std::string PredictingClient::error() const {
  if (!start_error_.empty()) return start_error_;
  if (core_.failed()) return core_.error();
  if (is_failure(connection_.state())) return connection_.last_error().to_string();
  return {};
}

void PredictingClient::disconnect(const std::string& reason) { connection_.disconnect(reason); }

}  // namespace client
