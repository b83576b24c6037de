#pragma once
// The world as the predicting client shows it to its own player (physics-view
// --predict): a client::PredictingClient joined as a player holding a zero input,
// its render state (the prediction, corrections smoothed) drawn as the frame.
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "client/predicting_client.h"
#include "game_messages.h"
#include "world_shapes.h"
#include "world_source.h"

namespace viewer {

class PredictedWorld : public WorldSource {
 public:
  // `rules`: the game's, run in the prediction (PredictingClientConfig::rules).
  explicit PredictedWorld(client::ClientConfig config,
                          std::shared_ptr<server::GameRules> rules = nullptr);

  // Connects and starts the world from the Welcome's; false with error() saying why.
  bool connect(std::chrono::milliseconds timeout);
  // Sends the inputs due and takes what arrived until `until`, or until the session
  // ended (false in connected()).
  void pump(std::chrono::steady_clock::time_point until);

  bool connected() const { return !ended_; }
  std::string error() const { return client_.error(); }
  const client::PredictingClient& client() const { return client_; }
  const WorldShapes& shapes() const override { return shapes_; }
  // Takes what arrived (1 ms at most) and the render state as a frame.
  const client::PlayoutFrame& update(double now) override;
  // The render state now, as a frame (the screenshot's).
  const client::PlayoutFrame& frame();
  std::optional<std::uint64_t> own_body() const override { return client_.core().own_body(); }
  bool send_game_message(std::string payload) override;
  const GameMessages& game_messages() const { return messages_; }
  std::vector<std::string> panel(const client::PlayoutFrame& frame,
                                 std::optional<std::uint64_t> followed) const override;

 private:
  // Bodies the prediction holds that the shapes do not (joined since the Welcome).
  void learn_shapes();

  client::PredictingClient client_;
  WorldShapes shapes_;
  GameMessages messages_;
  client::PlayoutFrame frame_;
  bool ended_ = false;
};

}  // namespace viewer
