#include "view.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

namespace server {
namespace {

using wire::PredictedBody;
using wire::PredictorMode;

// A quantized delta must stay an exact integer in a double on both ends; beyond
// this the body goes as an exact record instead.
constexpr double kMaxQuantizedDelta = 4503599627370496.0;  // 2^52

// A record carries the velocity alone when the position is within this share of the
// tolerance: the position then keeps room to drift before it must be sent.
constexpr double kVelocityOnlyShare = 0.5;

// Under a byte budget, bodies are ranked by how far they are out of tolerance and
// how near the client's own body they are: at this distance the weight halves.
constexpr double kPriorityHalfDistance = 10.0;

struct Candidate {
  const TruthBody* truth = nullptr;
  const PredictedBody* held = nullptr;  // null: the client holds no state for it
  double priority = 0.0;
  std::size_t bytes = 0;  // an estimate of its record's size
  bool own = false;
};

// Under a byte budget: the own body first, then the bodies the client does not hold
// (so that a full state completes in a bounded number of snapshots), then by priority.
int budget_tier(const Candidate& c) {
  if (c.own) return 0;
  return c.held == nullptr ? 1 : 2;
}

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

// Starts the records of one list: ids as gaps from the one before, and a mode entry
// ((index gap << 2) | mode) for each record whose mode changes. The caller adds the
// record's values to the list it returns.
template <class List>
class RecordStarts {
 public:
  explicit RecordStarts(List& list) : list_(list) {}
  List& start(std::uint64_t id, bool mode_changes, PredictorMode mode) {
    const auto index = static_cast<std::uint32_t>(list_.id_gaps_size());
    list_.add_id_gaps(id - last_id_);
    last_id_ = id;
    if (mode_changes) {
      list_.add_modes(((index - last_mode_) << 2) | static_cast<std::uint32_t>(mode));
      last_mode_ = index;
    }
    return list_;
  }

 private:
  List& list_;
  std::uint64_t last_id_ = 0;
  std::uint32_t last_mode_ = 0;  // record index of the last mode entry
};

void add_exact(RecordStarts<physics::wire::ExactBodies>& exact, std::uint64_t id, double x,
               double y, double vx, double vy, bool mode_changes, PredictorMode mode) {
  physics::wire::ExactBodies& list = exact.start(id, mode_changes, mode);
  list.add_x(x);
  list.add_y(y);
  list.add_vx(vx);
  list.add_vy(vy);
}

std::size_t varint_bytes(std::uint64_t v) {
  std::size_t n = 1;
  for (; v >= 0x80; v >>= 7) ++n;
  return n;
}

std::uint64_t zigzag(std::int64_t v) {
  return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
}

std::size_t quantized_bytes(double d) {
  if (!(std::fabs(d) < kMaxQuantizedDelta)) return 9;
  return varint_bytes(zigzag(static_cast<std::int64_t>(std::nearbyint(d))));
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

  // One walk over the world and the mirror, both in ascending id.
  const TruthBody* own_truth = own ? frame.find(*own) : nullptr;
  const auto& held = mirror_.bodies();
  std::vector<Candidate> candidates;
  std::vector<std::uint64_t> left;
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

  // The byte budget: the highest priorities first, each with what it waited.
  bodies_missing_ = 0;
  if (settings_.byte_budget > 0) {
    const PredictedBody zero{};
    for (Candidate& c : candidates) {
      const auto waited = waiting_priority_.find(c.truth->id);
      if (waited != waiting_priority_.end()) c.priority += waited->second;
      const PredictedBody& base = c.held != nullptr ? *c.held : zero;
      c.bytes = exact ? 34
                      : 3 + quantized_bytes((c.truth->x - base.x) / settings_.quantum.position) +
                            quantized_bytes((c.truth->y - base.y) / settings_.quantum.position) +
                            quantized_bytes((c.truth->vx - base.vx) / settings_.quantum.velocity) +
                            quantized_bytes((c.truth->vy - base.vy) / settings_.quantum.velocity);
    }
    std::vector<Candidate> ranked = candidates;
    std::stable_sort(ranked.begin(), ranked.end(), [](const Candidate& a, const Candidate& b) {
      const int ta = budget_tier(a);
      const int tb = budget_tier(b);
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

  // The records, ascending id; ids as gaps from the one before.
  physics::wire::QuantizedBodies& quantized = *message_.mutable_quantized();
  physics::wire::ExactBodies& exact_list = *message_.mutable_exact();
  physics::wire::VelocityBodies& velocities = *message_.mutable_velocities();
  RecordStarts<physics::wire::ExactBodies> exact_records(exact_list);
  RecordStarts<physics::wire::QuantizedBodies> quantized_records(quantized);
  RecordStarts<physics::wire::VelocityBodies> velocity_records(velocities);
  const PredictedBody zero{};
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
                                  [](double v) { return std::fabs(v) < kMaxQuantizedDelta; });
    // A body still well inside its position tolerance needs only its velocity
    // corrected: most records of a flowing pile are of that kind.
    const bool position_holds = c.held != nullptr &&
                                std::fabs(t.x - base.x) <= kVelocityOnlyShare * pos_tol &&
                                std::fabs(t.y - base.y) <= kVelocityOnlyShare * pos_tol;
    if (exact || !fits) {
      add_exact(exact_records, t.id, t.x, t.y, t.vx, t.vy, mode_changes, mode);
    } else if (position_holds) {
      physics::wire::VelocityBodies& list = velocity_records.start(t.id, mode_changes, mode);
      list.add_dvx(static_cast<std::int64_t>(std::nearbyint(d[2])));
      list.add_dvy(static_cast<std::int64_t>(std::nearbyint(d[3])));
      stats_.max_position_error = std::max(stats_.max_position_error, position_error(t, base));
    } else {
      physics::wire::QuantizedBodies& list = quantized_records.start(t.id, mode_changes, mode);
      const double n[4] = {std::nearbyint(d[0]), std::nearbyint(d[1]), std::nearbyint(d[2]),
                           std::nearbyint(d[3])};
      list.add_dx(static_cast<std::int64_t>(n[0]));
      list.add_dy(static_cast<std::int64_t>(n[1]));
      list.add_dvx(static_cast<std::int64_t>(n[2]));
      list.add_dvy(static_cast<std::int64_t>(n[3]));
      stats_.max_position_error =
          std::max({stats_.max_position_error, std::fabs(t.x - (base.x + n[0] * q)),
                    std::fabs(t.y - (base.y + n[1] * q))});
    }
  }
  if (quantized.id_gaps_size() == 0) message_.clear_quantized();
  if (exact_list.id_gaps_size() == 0) message_.clear_exact();
  if (velocities.id_gaps_size() == 0) message_.clear_velocities();
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
  physics::wire::ExactBodies& list = *full.mutable_exact();
  RecordStarts<physics::wire::ExactBodies> records(list);
  for (const PredictedBody& b : mirror_.bodies()) {
    add_exact(records, b.id, b.x, b.y, b.vx, b.vy, b.mode != PredictorMode::Ballistic, b.mode);
  }
  if (list.id_gaps_size() == 0) full.clear_exact();
  if (bodies_missing_ > 0) full.set_bodies_missing(bodies_missing_);
  full.set_view_hash(mirror_.hash());
  full_state_ = std::make_shared<const std::string>(full.SerializeAsString());
  return full_state_;
}

}  // namespace server
