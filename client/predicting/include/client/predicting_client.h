#pragma once
// A client that runs the world itself and predicts (GGPO-style rollback): it asks
// for the world and the input relay (Hello.want_world, Encoding::Inputs), sends its
// inputs ahead on its own clock (InputPacer), shows each at once in a world predicted
// to the tick of the newest input sent, and rolls back when the server's relayed
// ticks differ from the prediction (PredictionCore, prediction_core.h, says how).
// It links the physics core; the thin client (client/client.h) does not.
//
//   client::PredictingClientConfig config;
//   config.client.port = 7777;
//   client::PredictingClient player(config);
//   if (!player.connect(5s)) fail(player.error());
//   while (player.poll(next_frame, [](std::uint64_t tick) { return input(tick); }) !=
//          client::PollResult::Ended)
//     draw(player.render());
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "client/client.h"
#include "client/input_pacer.h"
#include "client/prediction_core.h"

namespace client {

struct PredictingClientConfig {
  // The connection. want_world and the view's encoding (Encoding::Inputs) are set by
  // the PredictingClient; the view's view_hash_interval sets how often the relay
  // carries the state hash.
  ClientConfig client;
  PacerConfig pacer;
  PredictionConfig prediction;
  // The game's rules, run in the prediction (PredictionCore::set_rules): the same
  // game as the server's, made for the same scene (server::load_rules_library loads
  // a game's rules library). Sets ClientConfig::run_rules.
  std::shared_ptr<server::GameRules> rules;
};

struct PredictingStats {
  PredictionStats prediction;
  std::uint64_t bytes_received = 0;  // on the wire, prefixes included
  std::uint64_t snapshots = 0;
  std::uint64_t full_state_requests_sent = 0;
};

enum class PollResult : std::uint8_t {
  Snapshot,   // a snapshot was taken (last_snapshot()) and the prediction advanced
  InputSent,  // an input went out; the prediction shows it
  Deadline,   // nothing happened before the deadline
  Ended,      // the session ended or the prediction failed (error())
};

class PredictingClient {
 public:
  explicit PredictingClient(PredictingClientConfig config);
  ~PredictingClient();
  PredictingClient(const PredictingClient&) = delete;
  PredictingClient& operator=(const PredictingClient&) = delete;

  // Connects and starts the world from the Welcome's. False when the connection
  // failed or the world did not parse (error() says which).
  bool connect(std::chrono::milliseconds timeout);

  // Sends the inputs that fall due (`input` is asked once per input sent, for its
  // tick, as InputPacer does) and takes what arrives, returning at the first input
  // sent, snapshot taken, or at `deadline`. A player's prediction then stands at
  // the newest tick whose input was sent (or max_rollback ticks past the confirmed
  // one); a spectator's at the confirmed tick.
  PollResult poll(std::chrono::steady_clock::time_point deadline,
                  const InputPacer::InputFor& input);

  // A game message for `tick` (Client::send_game_message), handed to the prediction
  // too, so that the rules predict its effect at that tick. False when it did not go
  // out.
  bool send_game_message(std::uint64_t tick, const std::string& payload);

  // What to draw: the prediction with corrections smoothed (PredictionCore::render).
  RenderState render() const { return core_.render(); }
  const PredictionCore& core() const { return core_; }
  // The newest snapshot taken (its header: ticks, input margins; no bodies).
  const std::optional<Snapshot>& last_snapshot() const { return last_snapshot_; }
  const Welcome& welcome() const { return connection_.welcome(); }
  Client& connection() { return connection_; }
  const InputPacer* pacer() const { return pacer_.get(); }
  PredictingStats stats() const;
  // Why the session or the prediction ended, for a person (empty while running).
  std::string error() const;

  void disconnect(const std::string& reason = "bye");

 private:
  PredictingClientConfig config_;
  Client connection_;
  std::unique_ptr<InputPacer> pacer_;
  PredictionCore core_;
  std::optional<Snapshot> last_snapshot_;
  std::uint64_t requests_sent_ = 0;
  std::string start_error_;
};

}  // namespace client
