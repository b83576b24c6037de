#pragma once
// The shapes of the world's bodies as the viewer knows them: every body of the
// Welcome, then those added and removed by each snapshot (docs/PROTOCOL.md, 3.2).
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "client/playout_buffer.h"
#include "client/types.h"

namespace viewer {

class WorldShapes {
 public:
  void reset(const std::vector<client::BodyShape>& bodies);
  void apply(const client::Snapshot& snapshot);

  const client::BodyShape* find(std::uint64_t id) const;
  const std::map<std::uint64_t, client::BodyShape>& all() const { return shapes_; }
  std::vector<client::BodyShape> list() const;
  std::size_t static_count() const { return statics_; }
  std::size_t dynamic_count() const { return shapes_.size() - statics_; }
  // Dynamic bodies added and removed since reset: players joining and leaving.
  std::uint64_t joined() const { return joined_; }
  std::uint64_t left() const { return left_; }
  // True for a moving body added by a snapshot (a player who joined after reset).
  bool joined_later(std::uint64_t id) const { return joined_ids_.count(id) != 0; }
  // The panel's line of body counts for `frame`: "bodies: N dynamic (S still), M static".
  std::string bodies_line(const client::PlayoutFrame& frame,
                          std::optional<std::uint64_t> followed) const;

 private:
  std::map<std::uint64_t, client::BodyShape> shapes_;
  std::size_t statics_ = 0;
  std::uint64_t joined_ = 0;
  std::uint64_t left_ = 0;
  std::set<std::uint64_t> joined_ids_;
};

}  // namespace viewer
