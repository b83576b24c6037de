#pragma once
// The world as a spectator sees it: a client connection, the shapes it was sent,
// and a playout buffer fed with every snapshot as it arrives. Joined as a player
// (ClientConfig::spectate false) it also sends a zero input every tick, on the
// client's clock as physics-client does, and the game messages its keys queue just
// before them.
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "client/client.h"
#include "client/input_pacer.h"
#include "client/playout_buffer.h"
#include "game_messages.h"
#include "world_shapes.h"
#include "world_source.h"

namespace viewer {

class LiveWorld : public WorldSource {
 public:
  explicit LiveWorld(client::ClientConfig config);

  // Connects and joins; false with error() saying why.
  bool connect(std::chrono::milliseconds timeout);
  // Takes every snapshot that has arrived, waiting up to `wait` for the first.
  // Returns how many were taken; false in connected() once the session ended.
  std::size_t pump(std::chrono::milliseconds wait);

  // Seconds on the steady clock since this object was made: the buffer's clock.
  double now() const;
  bool connected() const { return client_.state() == client::ConnectionState::Connected; }
  std::string error() const {
    return bad_welcome_.empty() ? client_.last_error().to_string() : bad_welcome_;
  }
  const client::Welcome& welcome() const { return client_.welcome(); }
  client::PlayoutBuffer& buffer() { return *buffer_; }
  const WorldShapes& shapes() const override { return shapes_; }
  // Takes what arrived (waiting 1 ms at most) and the buffer's frame for `now`.
  const client::PlayoutFrame& update(double now) override;
  std::optional<std::uint64_t> own_body() const override;
  bool send_game_message(std::string payload) override;
  const GameMessages& game_messages() const { return messages_; }
  // Bytes received over the last second or so, in kbit/s.
  double kbits_per_second() const;
  // How old the newest snapshot is (s since it was decoded); 0 when there is none.
  double newest_age() const;

  // The panel's lines: scene, tick and hash, bandwidth and age, clients, bodies.
  std::vector<std::string> panel(const client::PlayoutFrame& frame,
                                 std::optional<std::uint64_t> followed) const override;

 private:
  double seconds(std::chrono::steady_clock::time_point at) const;
  // The next snapshot within `wait`: through the pacer when playing.
  std::optional<client::Snapshot> next_snapshot(std::chrono::milliseconds wait);

  client::Client client_;
  std::unique_ptr<client::InputPacer> pacer_;  // playing only
  GameMessages messages_;
  std::chrono::steady_clock::time_point start_;
  std::optional<client::PlayoutBuffer> buffer_;
  WorldShapes shapes_;
  std::deque<std::pair<double, std::uint64_t>> traffic_;  // (time, bytes received)
  std::optional<std::chrono::steady_clock::time_point> newest_at_;
  std::string bad_welcome_;
};

}  // namespace viewer
