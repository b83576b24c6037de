#pragma once
// Where the viewer's world comes from: a live server (LiveWorld) or a client
// recording played again (ReplayWorld). The window and the screenshots draw
// either through this.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "client/playout_buffer.h"
#include "world_shapes.h"

namespace viewer {

class WorldSource {
 public:
  virtual ~WorldSource() = default;
  // Takes what arrived (or moves the playback on) and returns the frame to draw
  // for the caller's clock reading `now` (s).
  virtual const client::PlayoutFrame& update(double now) = 0;
  virtual const WorldShapes& shapes() const = 0;
  virtual std::vector<std::string> panel(const client::PlayoutFrame& frame,
                                         std::optional<std::uint64_t> followed) const = 0;
  // A key the source handles itself (an SDL_Keycode): playback controls. True when used.
  virtual bool key(int /*keycode*/) { return false; }
  // The keys of key(), for the panel's help line; empty when none.
  virtual std::string keys_help() const { return {}; }
  // The body this viewer plays, when it joined as a player: ringed and labelled.
  virtual std::optional<std::uint64_t> own_body() const { return std::nullopt; }
  // Queues a game message (a key bound with --key), sent before the next input.
  // False when this source cannot send one (a spectator, a replay).
  virtual bool send_game_message(std::string /*payload*/) { return false; }
};

}  // namespace viewer
