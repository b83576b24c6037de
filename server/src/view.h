#pragma once
// One view of the world: the settings a client asked for, and the mirror of what
// that client holds (its reconstruction, docs/PROTOCOL.md section 5). Each update
// compares the world with the mirror's prediction, puts the bodies that left it
// (by more than the tolerance) into records, and applies those records to the
// mirror with the client's own code (wire::Reconstruction::apply), so the mirror is
// the client's state bit for bit. Clients with equal settings and equal mirrors
// share one View, and so one encoding a tick. Socket-free: tests drive it alone.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "truth_frame.h"
#include "wire.pb.h"
#include "wire/predictor.h"
#include "wire/reconstruction.h"
#include "wire/view_settings.h"

namespace server {

struct ViewUpdateStats {
  std::size_t records = 0;          // bodies sent
  std::size_t left = 0;             // bodies that left the view
  std::size_t deferred = 0;         // out of tolerance, held back by the byte budget
  double max_position_error = 0.0;  // over the mirror after the update, vs the world
};

class View {
 public:
  View(wire::ViewSettings settings, wire::Predictor predictor);

  // Brings the mirror to `frame`. `own` is the client's own body (private views):
  // it is always in the view and goes first under a byte budget. `reset` forgets
  // the mirror first, so that every body is sent (a full state).
  void update(const TruthFrame& frame, std::optional<std::uint64_t> own, bool reset);

  // The last update as a serialized Snapshot (tick, hashes, records, left, full):
  // the part every client of this view shares. Empty of bodies when nothing moved
  // out of its prediction.
  // Shared with the sessions that write it: never copied per client or per tick.
  const std::shared_ptr<const std::string>& delta() const { return delta_; }
  bool delta_has_news() const { return delta_has_news_; }
  const ViewUpdateStats& last_stats() const { return stats_; }
  // The whole mirror as exact records, full = true: what a client joining this
  // view (or asking for a full state) gets, so that it holds the mirror exactly.
  const std::shared_ptr<const std::string>& full_state();

  const wire::ViewSettings& settings() const { return settings_; }
  const wire::Reconstruction& mirror() const { return mirror_; }

 private:
  struct Candidate;  // a body out of its prediction, to be sent (view.cpp)

  void update_full_encoding(const TruthFrame& frame, std::optional<std::uint64_t> own);
  std::vector<Candidate> out_of_prediction(const TruthFrame& frame,
                                           std::optional<std::uint64_t> own, bool exact,
                                           std::vector<std::uint64_t>& left);
  void keep_within_budget(std::vector<Candidate>& candidates, bool exact);
  void write_records(const std::vector<Candidate>& candidates, bool exact);
  bool in_interest(const TruthBody& body, const TruthBody* own) const;
  // Whether this update's delta carries the view hash (ViewSettings::view_hash_interval).
  bool hash_due(bool full);

  wire::ViewSettings settings_;
  wire::Predictor predictor_;
  wire::Reconstruction mirror_;
  // Fiedler's priority accumulators, for bodies held back by the byte budget: each
  // tick a body waits, its priority grows, so that none starves.
  std::map<std::uint64_t, double> waiting_priority_;
  physics::wire::Snapshot message_;
  std::shared_ptr<const std::string> delta_;
  bool delta_has_news_ = false;
  std::shared_ptr<const std::string> full_state_;  // null until asked for this update
  ViewUpdateStats stats_;
  std::uint64_t last_tick_ = 0;
  std::uint64_t state_hash_ = 0;
  std::uint32_t news_since_hash_ = 0;  // updates with news since the last with the hash
  std::uint32_t bodies_missing_ = 0;   // in the view, not held: the budget held them back
};

}  // namespace server
