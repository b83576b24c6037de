// A view's policy: which bodies go to its clients this tick, and how each goes
// (the predictor that carries it, quantized, velocity only or exact), under its
// tolerances, its area of interest and its byte budget. The records themselves are
// written by wire::SnapshotRecordWriter, next to the reader the clients run.
#include "view.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include "wire/snapshot_records.h"

namespace server {

using wire::PredictedBody;
using wire::PredictorMode;

// A body out of its prediction (or not held), to be sent unless the budget holds it.
struct View::Candidate {
  const TruthBody* truth = nullptr;
  const PredictedBody* held = nullptr;  // null: the client holds no state for it
  double priority = 0.0;
  std::size_t bytes = 0;  // an estimate of its record's size
  bool own = false;

  // Under a byte budget: the own body first, then the bodies the client does not hold
  // (so that a full state completes in a bounded number of snapshots), then by
  // priority.
  int budget_tier() const {
    if (own) return 0;
    return held == nullptr ? 1 : 2;
  }
};

namespace {

// A record carries the velocity alone when the position is within this share of the
// tolerance: the position then keeps room to drift before it must be sent.
constexpr double kVelocityOnlyShare = 0.5;

// Under a byte budget, bodies are ranked by how far they are out of tolerance and
// how near the client's own body they are: at this distance the weight halves.
constexpr double kPriorityHalfDistance = 10.0;

double largest_error(const TruthBody& t, const PredictedBody& m, double position_scale,
                     double velocity_scale) {
  return std::max({std::fabs(t.x - m.x) / position_scale, std::fabs(t.y - m.y) / position_scale,
                   std::fabs(t.vx - m.vx) / velocity_scale,
                   std::fabs(t.vy - m.vy) / velocity_scale});
}

double position_error(const TruthBody& t, const PredictedBody& m) {
  return std::max(std::fabs(t.x - m.x), std::fabs(t.y - m.y));
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

bool changed_at_all(const TruthBody& t, const PredictedBody& m) {
  return !same_bits(t.x, m.x) || !same_bits(t.y, m.y) || !same_bits(t.vx, m.vx) ||
         !same_bits(t.vy, m.vy);
}

// How far `mode` would have missed the last tick: the body's state a tick ago,
// carried one tick by it, against its state now (in tolerances).
double miss(const wire::Predictor& predictor, const TruthBody& t, PredictorMode mode,
            double pos_tol, double vel_tol) {
  PredictedBody b;
  b.x = t.previous_x;
  b.y = t.previous_y;
  b.vx = t.previous_vx;
  b.vy = t.previous_vy;
  b.mode = mode;
  predictor.advance(b);
  return largest_error(t, b, pos_tol, vel_tol);
}

// The predictor that should carry the body from here: the server's choice, told
// to the client in the record (the client never guesses). A dynamic body keeps its mode
// unless another would have predicted the last tick clearly better (by half), so
// that bodies jostling in a pile do not pay a mode change with every record.
PredictorMode choose_mode(const wire::Predictor& predictor, const TruthBody& t,
                          PredictorMode current, double pos_tol, double vel_tol) {
  // A kinematic body moves by its velocity alone, awake or not (it never sleeps):
  // Glide carries it, and gravity (Ballistic) never acts on it.
  if (t.kinematic) return PredictorMode::Glide;
  if (!t.awake) return PredictorMode::Hold;
  PredictorMode best = current;
  double best_miss = miss(predictor, t, current, pos_tol, vel_tol);
  const double kept = best_miss;
  for (const PredictorMode m :
       {PredictorMode::Ballistic, PredictorMode::Glide, PredictorMode::Hold}) {
    if (m == current) continue;
    const double e = miss(predictor, t, m, pos_tol, vel_tol);
    if (e < best_miss) {
      best = m;
      best_miss = e;
    }
  }
  return best_miss < 0.5 * kept ? best : current;
}

}  // namespace

View::View(wire::ViewSettings settings, wire::Predictor predictor)
    : settings_(settings), predictor_(predictor) {}

bool View::in_interest(const TruthBody& body, const TruthBody* own) const {
  switch (settings_.interest) {
    case wire::InterestKind::World:
      return true;
    case wire::InterestKind::Radius: {
      if (own == nullptr) return false;
      const double dx = body.x - own->x;
      const double dy = body.y - own->y;
      return dx * dx + dy * dy <= settings_.interest_radius * settings_.interest_radius;
    }
    case wire::InterestKind::Rect: {
      const auto& r = settings_.interest_rect;
      return body.x >= r.min_x() && body.x <= r.max_x() && body.y >= r.min_y() &&
             body.y <= r.max_y();
    }
  }
  return false;
}

// Every snapshot of the full encoding is a full state; the client holds its bodies
// as sent (mode Hold), and the view hash covers them as in the other encodings.
void View::update_full_encoding(const TruthFrame& frame, std::optional<std::uint64_t> own) {
  message_.set_full(true);
  const TruthBody* own_truth = own ? frame.find(*own) : nullptr;
  for (const TruthBody& t : frame.bodies) {
    if (!(own && t.id == *own) && !in_interest(t, own_truth)) continue;
    physics::wire::BodyState* state = message_.add_bodies();
    state->set_body_id(t.id);
    state->set_x(t.x);
    state->set_y(t.y);
    state->set_vx(t.vx);
    state->set_vy(t.vy);
    ++stats_.records;
  }
  const std::string error = mirror_.apply(message_, predictor_, settings_.quantum);
  (void)error;  // ascending ids of finite states: well formed
  message_.set_view_hash(mirror_.hash());
  delta_has_news_ = true;
}

void View::update(const TruthFrame& frame, std::optional<std::uint64_t> own, bool reset) {
  stats_ = {};
  message_.Clear();
  full_state_.reset();
  last_tick_ = frame.tick;
  state_hash_ = frame.state_hash;
  message_.set_tick(frame.tick);
  if (settings_.state_hash) message_.set_state_hash(frame.state_hash);
  if (settings_.encoding == physics::wire::ENCODING_FULL) {
    update_full_encoding(frame, own);
    delta_ = std::make_shared<const std::string>(message_.SerializeAsString());
    return;
  }
  if (settings_.encoding == physics::wire::ENCODING_INPUTS) {
    // No body records: the server appends the relayed ticks to each client's own
    // bytes. Every tick is news, since the client steps its world by them.
    delta_has_news_ = true;
    delta_ = std::make_shared<const std::string>(message_.SerializeAsString());
    return;
  }
  const bool exact = settings_.encoding == physics::wire::ENCODING_EXACT;
  if (reset) mirror_.clear();
  if (mirror_.started()) mirror_.advance_to(frame.tick, predictor_);

  std::vector<std::uint64_t> left;
  std::vector<Candidate> candidates = out_of_prediction(frame, own, exact, left);
  bodies_missing_ = 0;
  if (settings_.byte_budget > 0) keep_within_budget(candidates, exact);
  write_records(candidates, exact);
  for (std::size_t i = 0; i < left.size(); ++i) {
    message_.add_left_gaps(i == 0 ? left[i] : left[i] - left[i - 1]);
  }
  if (reset) message_.set_full(true);
  if (bodies_missing_ > 0) message_.set_bodies_missing(bodies_missing_);
  stats_.records = candidates.size();
  stats_.left = left.size();

  // The mirror takes the records exactly as the client will.
  const std::string error = mirror_.apply(message_, predictor_, settings_.quantum);
  (void)error;  // our own records are well formed; the tests check apply() on bad ones
  delta_has_news_ = !candidates.empty() || !left.empty() || reset;
  if (hash_due(reset)) message_.set_view_hash(mirror_.hash());
  delta_ = std::make_shared<const std::string>(message_.SerializeAsString());
}

// One walk over the world and the mirror, both in ascending id: the bodies in the
// view that left their prediction (or that the client does not hold), and in `left`
// the bodies the client holds that are gone or out of the view.
std::vector<View::Candidate> View::out_of_prediction(const TruthFrame& frame,
                                                     std::optional<std::uint64_t> own, bool exact,
                                                     std::vector<std::uint64_t>& left) {
  const TruthBody* own_truth = own ? frame.find(*own) : nullptr;
  const auto& held = mirror_.bodies();
  std::vector<Candidate> candidates;
  std::size_t m = 0;
  const double pos_tol = settings_.position_tolerance;
  const double vel_tol = settings_.velocity_tolerance;
  for (const TruthBody& t : frame.bodies) {
    while (m < held.size() && held[m].id < t.id) left.push_back(held[m++].id);  // gone
    const PredictedBody* mine = m < held.size() && held[m].id == t.id ? &held[m++] : nullptr;
    const bool is_own = own && t.id == *own;
    if (!is_own && !in_interest(t, own_truth)) {
      if (mine != nullptr) left.push_back(t.id);
      continue;
    }
    double error_ratio = 10.0;  // a body the client does not hold yet
    if (mine != nullptr) {
      if (exact) {
        if (!changed_at_all(t, *mine)) continue;
        error_ratio = 1.0;
      } else {
        error_ratio = largest_error(t, *mine, pos_tol, vel_tol);
        if (error_ratio <= 1.0) {
          stats_.max_position_error = std::max(stats_.max_position_error, position_error(t, *mine));
          continue;
        }
      }
    }
    Candidate c;
    c.truth = &t;
    c.held = mine;
    c.priority = 1.0 + error_ratio;
    if (own_truth != nullptr) {
      const double distance = std::hypot(t.x - own_truth->x, t.y - own_truth->y);
      c.priority /= 1.0 + distance / kPriorityHalfDistance;
    }
    c.own = is_own;
    candidates.push_back(c);
  }
  while (m < held.size()) left.push_back(held[m++].id);
  return candidates;
}

// The byte budget: the highest priorities first, each with what it waited; the rest
// wait, their priorities kept for the next update.
void View::keep_within_budget(std::vector<Candidate>& candidates, bool exact) {
  const PredictedBody zero{};
  for (Candidate& c : candidates) {
    const auto waited = waiting_priority_.find(c.truth->id);
    if (waited != waiting_priority_.end()) c.priority += waited->second;
    const PredictedBody& base = c.held != nullptr ? *c.held : zero;
    c.bytes =
        exact ? wire::kExactRecordBytes
              : wire::quantized_record_bytes((c.truth->x - base.x) / settings_.quantum.position,
                                             (c.truth->y - base.y) / settings_.quantum.position,
                                             (c.truth->vx - base.vx) / settings_.quantum.velocity,
                                             (c.truth->vy - base.vy) / settings_.quantum.velocity);
  }
  std::vector<Candidate> ranked = candidates;
  std::stable_sort(ranked.begin(), ranked.end(), [](const Candidate& a, const Candidate& b) {
    const int ta = a.budget_tier();
    const int tb = b.budget_tier();
    return ta != tb ? ta < tb : a.priority > b.priority;
  });
  std::map<std::uint64_t, double> still_waiting;
  std::vector<std::uint64_t> chosen;
  std::size_t used = 0;
  bool missing_sent = false;
  for (const Candidate& c : ranked) {
    // One body not held goes in every snapshot, whatever its size: the bound on
    // completing a full state (docs/PROTOCOL.md, section 5.9) rests on it.
    const bool first_missing = c.held == nullptr && !c.own && !missing_sent;
    if (used + c.bytes <= settings_.byte_budget || chosen.empty() || first_missing) {
      used += c.bytes;
      chosen.push_back(c.truth->id);
      if (c.held == nullptr && !c.own) missing_sent = true;
    } else {
      still_waiting.emplace(c.truth->id, c.priority);
      ++stats_.deferred;
      if (c.held == nullptr) ++bodies_missing_;
      if (c.held != nullptr) {
        stats_.max_position_error =
            std::max(stats_.max_position_error, position_error(*c.truth, *c.held));
      }
    }
  }
  std::sort(chosen.begin(), chosen.end());
  std::erase_if(candidates, [&](const Candidate& c) {
    return !std::binary_search(chosen.begin(), chosen.end(), c.truth->id);
  });
  waiting_priority_ = std::move(still_waiting);
}

// The records, ascending id: each body with the predictor that carries it from here,
// as exact values, quantized deltas, or its velocity alone.
void View::write_records(const std::vector<Candidate>& candidates, bool exact) {
  wire::SnapshotRecordWriter records(message_);
  const PredictedBody zero{};
  const double pos_tol = settings_.position_tolerance;
  const double vel_tol = settings_.velocity_tolerance;
  for (const Candidate& c : candidates) {
    const TruthBody& t = *c.truth;
    const PredictedBody& base = c.held != nullptr ? *c.held : zero;
    const PredictorMode mode =
        exact ? PredictorMode::Hold : choose_mode(predictor_, t, base.mode, pos_tol, vel_tol);
    const bool mode_changes = mode != base.mode;
    const double q = settings_.quantum.position;
    const double qv = settings_.quantum.velocity;
    const double d[4] = {(t.x - base.x) / q, (t.y - base.y) / q, (t.vx - base.vx) / qv,
                         (t.vy - base.vy) / qv};
    const bool fits = std::all_of(std::begin(d), std::end(d),
                                  [](double v) { return std::fabs(v) < wire::kMaxQuantizedDelta; });
    // A body still well inside its position tolerance needs only its velocity
    // corrected: most records of a flowing pile are of that kind.
    const bool position_holds = c.held != nullptr &&
                                std::fabs(t.x - base.x) <= kVelocityOnlyShare * pos_tol &&
                                std::fabs(t.y - base.y) <= kVelocityOnlyShare * pos_tol;
    if (exact || !fits) {
      records.add_exact(t.id, t.x, t.y, t.vx, t.vy, mode_changes, mode);
    } else if (position_holds) {
      records.add_velocity(t.id, static_cast<std::int64_t>(std::nearbyint(d[2])),
                           static_cast<std::int64_t>(std::nearbyint(d[3])), mode_changes, mode);
      stats_.max_position_error = std::max(stats_.max_position_error, position_error(t, base));
    } else {
      const double n[4] = {std::nearbyint(d[0]), std::nearbyint(d[1]), std::nearbyint(d[2]),
                           std::nearbyint(d[3])};
      records.add_quantized(t.id, static_cast<std::int64_t>(n[0]), static_cast<std::int64_t>(n[1]),
                            static_cast<std::int64_t>(n[2]), static_cast<std::int64_t>(n[3]),
                            mode_changes, mode);
      stats_.max_position_error =
          std::max({stats_.max_position_error, std::fabs(t.x - (base.x + n[0] * q)),
                    std::fabs(t.y - (base.y + n[1] * q))});
    }
  }
  records.finish();
}

// Every member of the view is sent every update with news (a member that cannot be
// is moved to a view of its own), so counting them here counts them per client.
// A snapshot without news may reach some members only (a heartbeat): it always
// carries the hash, and does not count.
bool View::hash_due(bool full) {
  if (!delta_has_news_) return true;
  ++news_since_hash_;
  if (!full && news_since_hash_ < settings_.view_hash_interval) return false;
  news_since_hash_ = 0;
  return true;
}

const std::shared_ptr<const std::string>& View::full_state() {
  if (settings_.encoding == physics::wire::ENCODING_FULL ||
      settings_.encoding == physics::wire::ENCODING_INPUTS) {
    return delta_;
  }
  if (full_state_) return full_state_;
  physics::wire::Snapshot full;
  full.set_tick(last_tick_);
  if (settings_.state_hash) full.set_state_hash(state_hash_);
  full.set_full(true);
  wire::SnapshotRecordWriter records(full);
  for (const PredictedBody& b : mirror_.bodies()) {
    records.add_exact(b.id, b.x, b.y, b.vx, b.vy, b.mode != PredictorMode::Ballistic, b.mode);
  }
  records.finish();
  if (bodies_missing_ > 0) full.set_bodies_missing(bodies_missing_);
  full.set_view_hash(mirror_.hash());
  full_state_ = std::make_shared<const std::string>(full.SerializeAsString());
  return full_state_;
}

}  // namespace server
