// One sub-step of the world, in the lecture's order:
//   friction; acceleration and gravity; move on Y, collide on Y; move on X,
//   collide on X; restitution.
// plus what the lecture leaves out and a server needs: a broadphase, swept motion
// against static bodies (nothing tunnels), shock propagation for stacks, and sleep.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

#include "branchless.h"
#include "physics/formulas.h"
#include "sweep.h"
#include "world_impl.h"

namespace phys {

namespace {

constexpr std::uint32_t kNone = UINT32_MAX;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// A contact whose normal is within 72.5 degrees of "up" (cosine 0.3) carries weight
// (supports). At 60 degrees, a circle sunk into a narrow gap between two resting
// neighbours, meeting them less than 30 degrees above level, was no load of theirs:
// the passes split its pushes half and half, pressing them apart into their
// pockets. Hard case 6's pile without friction then fell asleep only at 60 s, with
// rows of side-by-side circles compressed end to end (0.0148 m); at 72.5 degrees it
// sleeps at 43.5 s with 0.0042 m (docs/PHYSICS.md, "Stacks: shock propagation").
constexpr double kSupportCosine = 0.3;
// A normal this close to gravity's line is a face resting on a face.
constexpr double kAlongGravity = 1.0 - 1.0e-9;
// Time-of-impact stops per body, axis and sub-step (a bounce, then maybe another).
constexpr int kMaxHitsPerMove = 4;
// Candidate boxes grow by this fraction of a body's smaller half extent.
constexpr double kPushMargin = 0.1;
// Pairs are found with boxes grown by this fraction more, and reused while every
// body stays inside its grown box.
constexpr double kFatMargin = 0.1;
// How many candidate pairs ahead the position passes prefetch scattered bodies.
constexpr std::uint32_t kPrefetchAhead = 8;
// Where a Body's cold line begins (its third cache line: still_time and after).
constexpr std::size_t kColdLineOffset = 2 * 64;
static_assert(offsetof(Body, still_time) >= kColdLineOffset &&
                  offsetof(Body, still_anchor) + sizeof(Vec2) <= 3 * 64,
              "update_sleep prefetches the line of still_time and still_anchor");
// Up to this many static and sleeping bodies are tested one by one, not through
// their grid.
constexpr std::size_t kFewFixed = 8;

double component(const Vec2& v, int axis) { return axis == 0 ? v.x : v.y; }
double& component(Vec2& v, int axis) { return axis == 0 ? v.x : v.y; }

class PhaseTimer {
 public:
  PhaseTimer(bool on, double& into) : on_(on), into_(into) {
    if (on_) start_ = std::chrono::steady_clock::now();
  }
  ~PhaseTimer() {
    if (on_) {
      into_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
  }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  bool on_;
  double& into_;
  std::chrono::steady_clock::time_point start_{};
};

}  // namespace

class StepRunner {
 public:
  StepRunner(WorldImpl& world, double h)
      : w_(world),
        s_(world.settings),
        h_(h),
        gravity_on_(s_.gravity.x != 0.0 || s_.gravity.y != 0.0),
        up_(gravity_on_ ? -s_.gravity * (1.0 / length(s_.gravity)) : Vec2{0.0, 1.0}),
        rest_speed_(s_.rest_speed > 0.0 ? s_.rest_speed : 2.0 * length(s_.gravity) * h),
        shock_(s_.shock_propagation && gravity_on_),
        hold_(s_.hold_resting_support && gravity_on_),
        speculative_margin_(0.5 * length(s_.gravity) * h * h),
        // (Never, for a limit so large that its square would overflow.)
        surely_slow_(s_.max_speed < 1.0e150 ? (0.5 * s_.max_speed) * (0.5 * s_.max_speed) : -1.0) {}

  void run() {
    if (w_.lists_dirty_) w_.rebuild_lists();
    w_.counters.sleeping_bodies_skipped += w_.fixed_sleeping_;
    if (w_.active_.empty()) return;
    {
      PhaseTimer t(s_.profile, w_.profile.integrate);
      order_by_height();
      integrate();
    }
    {
      PhaseTimer t(s_.profile, w_.profile.broadphase);
      find_candidates();
    }
    w_.contact_of_candidate_.assign(w_.candidates_.size(), kNone);
    w_.contact_normal_.resize(w_.candidates_.size());
    w_.contact_near_miss_.resize(w_.candidates_.size());
    w_.contact_gap_.resize(w_.candidates_.size());
    if (any_active_box_) {
      move(1);
      collide_boxes_on<1>();
      move(0);
    } else {
      move_both_axes();
    }
    collide_on_x();
    {
      PhaseTimer t(s_.profile, w_.profile.resolve);
      restitution();  // and, with hold_, update_held's work
    }
    {
      PhaseTimer t(s_.profile, w_.profile.sleep);
      hold_in_bounds();
      update_sleep();
    }
  }

 private:
  Body& body(std::uint32_t slot) { return w_.bodies[slot]; }
  // The loops over the awake bodies in processing order read them where their
  // slots are: in a pile that has flowed, all over memory, where the hardware's
  // prefetcher cannot follow. Each asks for the body kPrefetchAhead places on.
  void prefetch_ahead(std::size_t p) const {
    if (p + kPrefetchAhead < w_.active_.size()) {
      __builtin_prefetch(&w_.bodies[w_.active_[p + kPrefetchAhead]]);
    }
  }
  // The same, for a loop that reads a body's cold line too (still_time and after).
  void prefetch_ahead_with_cold_line(std::size_t p) const {
    if (p + kPrefetchAhead < w_.active_.size()) {
      const Body* b = &w_.bodies[w_.active_[p + kPrefetchAhead]];
      __builtin_prefetch(b);
      __builtin_prefetch(reinterpret_cast<const char*>(b) + kColdLineOffset);
    }
  }
  // Awake bodies are processed from the lowest (along gravity) up, so that a body's
  // supports are resolved before it. The order persists between steps and is
  // nearly sorted, so insertion sort is about O(N).
  void order_by_height() {
    auto& order = w_.active_;
    auto& keys = w_.sort_keys_;
    keys.resize(order.size());
    std::size_t jumps = 0;  // neighbours in the order that are not neighbours in slots
    for (std::size_t p = 1; p < order.size(); ++p) {
      jumps += static_cast<std::size_t>(order[p] != order[p - 1] + 1);
    }
    // Far from slot order (a pile that has flowed), the passes over the bodies read
    // them all over memory and prefetch them; in slot order (a stack, a fresh scene)
    // the hardware streams them on its own.
    scattered_ = 4 * jumps > order.size();
    for (std::size_t p = 0; p < order.size(); ++p) {
      if (scattered_) prefetch_ahead(p);
      keys[p] = dot(body(order[p]).position, up_);
    }
    if (w_.joined_ > 0) merge_joined();
    // Heights within the slop are ties, broken by slot: a row of boxes at one height
    // keeps its order although rounding moves them by 1e-16 (and the candidate pairs,
    // grouped by position in this order, can then be reused).
    const double tie = s_.slop;
    const auto before = [tie](double ka, std::uint32_t a, double kb, std::uint32_t b) {
      return ka < kb - tie || (ka <= kb + tie && a < b);
    };
    std::size_t moves = 0;
    const std::size_t budget = 8 * order.size() + 64;
    for (std::size_t p = 1; p < order.size() && moves <= budget; ++p) {
      const double key = keys[p];
      const std::uint32_t slot = order[p];
      std::size_t q = p;
      while (q > 0 && before(key, slot, keys[q - 1], order[q - 1])) {
        keys[q] = keys[q - 1];
        order[q] = order[q - 1];
        --q;
        ++moves;
      }
      keys[q] = key;
      order[q] = slot;
    }
    order_changed_ = order_changed_ || moves > 0;
    if (moves > budget) {  // far from sorted (first step, a shuffle): sort outright
      std::vector<std::pair<double, std::uint32_t>> keyed(order.size());
      for (std::size_t p = 0; p < order.size(); ++p) {
        keyed[p] = {dot(body(order[p]).position, up_), order[p]};
      }
      std::sort(keyed.begin(), keyed.end());
      for (std::size_t p = 0; p < order.size(); ++p) order[p] = keyed[p].second;
    }
  }

  // The bodies that joined the list at its rebuild (woken or added) wait at its end
  // in slot order: sorted by height among themselves and merged into the kept
  // bodies' order in one walk, so that the insertion sort has only the usual small
  // moves left (from the end, each would walk past most of the list).
  void merge_joined() {
    auto& order = w_.active_;
    auto& keys = w_.sort_keys_;
    const std::size_t n = order.size();
    const std::size_t kept = n - w_.joined_;
    w_.joined_ = 0;
    auto& keyed = w_.keyed_order_;
    keyed.resize(n);
    for (std::size_t p = 0; p < n; ++p) keyed[p] = {keys[p], order[p]};
    std::sort(keyed.begin() + static_cast<std::ptrdiff_t>(kept), keyed.end());
    std::size_t i = 0;
    std::size_t j = kept;
    for (std::size_t p = 0; p < n; ++p) {
      const bool take_kept = j == n || (i < kept && !(keyed[j] < keyed[i]));
      const auto& next = take_kept ? keyed[i++] : keyed[j++];
      keys[p] = next.first;
      order[p] = next.second;
    }
    order_changed_ = true;
  }

  // Friction, acceleration and gravity: the free motion of each awake body over the
  // sub-step, per axis. The moves below apply it.
  void integrate() {
    if (scattered_) {
      integrate<true>();
    } else {
      integrate<false>();
    }
  }

  // In two builds, as resolve_passes: with prefetching for bodies scattered in
  // memory, and without it, so that a stack's loop carries no trace of it.
  template <bool kPrefetch>
  void integrate() {
    const std::size_t n = w_.active_.size();
    w_.step_velocity_.resize(n);
    w_.step_displacement_.resize(n);
    bool any_friction = false;
    any_contact_friction_ = false;
    // The broadphase's reuse check rides along (it reads the same body and the
    // displacement just computed): every body still inside the box its pairs were
    // found with, in the same order, and those pairs are still a superset of the
    // ones that can touch (Box2D's fat boxes). The first body outside ends it.
    bool all_inside = w_.candidates_valid_ && !order_changed_ && w_.fat_boxes_.size() == n;
    // When the pairs are sure to be found anew (the order or the lists changed, as in
    // every step of a flowing pile), the boxes they will be found with are made here,
    // while the body is in cache. A resting stack, whose pairs are kept, pays nothing.
    fat_made_ = !all_inside;
    auto& next_fat = w_.next_fat_boxes_;
    if (fat_made_) next_fat.resize(n);
    any_active_box_ = false;
    any_active_circle_ = false;
    for (std::size_t p = 0; p < n; ++p) {
      if (kPrefetch) prefetch_ahead(p);
      Body& b = body(w_.active_[p]);
      b.correction = {};
      any_friction = any_friction || b.friction.x != 0.0 || b.friction.y != 0.0;
      any_contact_friction_ = any_contact_friction_ || b.contact_friction > 0.0;
      any_active_box_ = any_active_box_ || b.shape == Shape::Box;
      any_active_circle_ = any_active_circle_ || b.shape == Shape::Circle;
      const Vec2 a = driving_acceleration(b);
      const AxisMotion mx =
          integrate_axis(s_.integrator, b.position.x, b.velocity.x, a.x, b.friction.x, h_);
      const AxisMotion my =
          integrate_axis(s_.integrator, b.position.y, b.velocity.y, a.y, b.friction.y, h_);
      Vec2 v{mx.velocity, my.velocity};
      Vec2 d{mx.position - b.position.x, my.position - b.position.y};
      // A resting body moves as if its contacts still held it (it does not sink
      // into its support, nor creep along it when friction holds a push), but its
      // velocity keeps all of its acceleration: the contacts must take that away
      // again, which is how the next step knows they are there.
      if (b.held.x != 0.0) {
        d.x = integrate_axis(s_.integrator, b.position.x, b.velocity.x, a.x + b.held.x,
                             b.friction.x, h_)
                  .position -
              b.position.x;
      }
      if (b.held.y != 0.0) {
        d.y = integrate_axis(s_.integrator, b.position.y, b.velocity.y, a.y + b.held.y,
                             b.friction.y, h_)
                  .position -
              b.position.y;
      }
      // A squared speed below a quarter of the limit's square is surely under the
      // limit (sqrt of it is about half the limit): no square root for the usual body.
      const double speed_squared = dot(v, v);
      const double speed = speed_squared <= surely_slow_ ? 0.0 : std::sqrt(speed_squared);
      if (speed > s_.max_speed) {  // the world stays finite: speeds are capped
        const double scale = s_.max_speed / speed;
        v = v * scale;
        d = d * scale;
        ++w_.counters.speed_clamps;
      }
      w_.step_velocity_[p] = v;
      w_.step_displacement_[p] = d;
      if (fat_made_) {
        next_fat[p] = fattened(b, needed_box(b, d));
      } else if (all_inside) {
        const Aabb box = needed_box(b, d);
        const Aabb& fat = w_.fat_boxes_[p];
        all_inside = box.min.x >= fat.min.x && box.min.y >= fat.min.y && box.max.x <= fat.max.x &&
                     box.max.y <= fat.max.y;
      }
    }
    all_inside_ = all_inside;
    w_.counters.bodies_integrated += n;
    if (any_contact_friction_) {
      w_.step_start_.resize(n);
      for (std::size_t p = 0; p < n; ++p) w_.step_start_[p] = body(w_.active_[p]).position;
    }
    if (any_friction) ++w_.counters.friction_passes;
    if (gravity_on_) ++w_.counters.gravity_passes;
  }

  // What drives a body: gravity and its own acceleration.
  Vec2 driving_acceleration(const Body& b) const {
    return gravity_on_ ? b.acceleration + s_.gravity : b.acceleration;
  }

  // The acceleration a body moves by: what drives it, less what its contacts held
  // back last sub-step (see Body::held).
  Vec2 moving_acceleration(const Body& b) const {
    return gravity_on_ ? driving_acceleration(b) + b.held : b.acceleration;
  }

  // What a body may reach this sub-step, given its free-motion displacement d:
  // beyond its own motion, a body can be pushed by its neighbours while contacts
  // are resolved, and a tenth of its size keeps those pushes within the pairs found.
  Aabb needed_box(const Body& b, Vec2 d) const {
    const double pushed = kPushMargin * std::min(b.half.x, b.half.y) + s_.slop;
    const Vec2 margin{std::fabs(d.x) + pushed, std::fabs(d.y) + pushed};
    Aabb box = b.bounds();
    box.min -= margin;
    box.max += margin;
    return box;
  }

  // The box a body's pairs are found with: what it needs, grown so that the pairs
  // may be kept while it stays inside (see integrate()).
  static Aabb fattened(const Body& b, const Aabb& needed) {
    const double extra = kFatMargin * std::min(b.half.x, b.half.y);
    return {needed.min - Vec2{extra, extra}, needed.max + Vec2{extra, extra}};
  }

  // Candidate pairs for the whole sub-step: boxes fattened by how far each body can
  // move in it, so the pairs hold for both axis moves.
  void find_candidates() {
    const std::size_t n = w_.active_.size();
    if (all_inside_) {  // integrate() found the last pairs still good (fat boxes)
      ++w_.counters.broadphase_reuses;
      return;
    }
    auto& fat = w_.fat_boxes_;
    if (fat_made_) {
      fat.swap(w_.next_fat_boxes_);
    } else {  // the last pairs looked reusable until a body left its box
      fat.resize(n);
      for (std::size_t p = 0; p < n; ++p) {
        if (scattered_) prefetch_ahead(p);
        const Body& b = body(w_.active_[p]);
        fat[p] = fattened(b, needed_box(b, w_.step_displacement_[p]));
      }
    }
    w_.active_grid_.build(fat);
    w_.active_grid_.find_pairs(w_.active_pairs_);

    w_.candidates_.clear();
    w_.first_candidate_.assign(n + 1, 0);
    const bool few_fixed = w_.fixed_boxes_.size() <= kFewFixed;
    std::size_t next_pair = 0;
    for (std::uint32_t p = 0; p < n; ++p) {
      w_.first_candidate_[p] = static_cast<std::uint32_t>(w_.candidates_.size());
      if (few_fixed) {
        // A handful of static bodies (a container's walls): testing each is cheaper
        // than a grid query, and gives the same ones in the same (ascending) order.
        for (std::uint32_t f = 0; f < w_.fixed_boxes_.size(); ++f) {
          if (boxes_intersect(fat[p], w_.fixed_boxes_[f])) {
            w_.candidates_.push_back({w_.active_[p], w_.fixed_[f], p, kNone, true});
          }
        }
      } else if (w_.fixed_grid_.size() > 0) {
        w_.fixed_grid_.find_overlaps(fat[p], w_.overlaps_);
        for (std::uint32_t f : w_.overlaps_) {
          w_.candidates_.push_back({w_.active_[p], w_.fixed_[f], p, kNone, true});
        }
      }
      while (next_pair < w_.active_pairs_.size() && w_.active_pairs_[next_pair].a == p) {
        const std::uint32_t q = w_.active_pairs_[next_pair].b;
        w_.candidates_.push_back({w_.active_[p], w_.active_[q], p, q, false});
        ++next_pair;
      }
    }
    w_.first_candidate_[n] = static_cast<std::uint32_t>(w_.candidates_.size());
    w_.candidates_valid_ = true;
  }

  // Move every awake body along one axis. Against static and sleeping bodies the
  // move is swept: it stops at the time of impact, bounces, and goes on.
  void move(int axis) {
    PhaseTimer t(s_.profile, w_.profile.integrate);
    if (scattered_) {
      move<true>(axis, axis);
    } else {
      move<false>(axis, axis);
    }
  }

  // With no awake box there is no collision on Y between the moves: each body moves
  // on Y and then on X in one walk over the bodies instead of two. The result is the
  // two walks' bit for bit, because a body's moves read no other awake body (the
  // sweep meets static and sleeping bodies only), and a walk over bodies scattered
  // in memory costs as much as the moves themselves.
  void move_both_axes() {
    PhaseTimer t(s_.profile, w_.profile.integrate);
    if (scattered_) {
      move<true>(1, 0);
    } else {
      move<false>(1, 0);
    }
  }

  // Moves each body on first_axis, then down to last_axis.
  template <bool kPrefetch>
  void move(int first_axis, int last_axis) {
    for (std::uint32_t p = 0; p < w_.active_.size(); ++p) {
      if (kPrefetch) prefetch_ahead(p);
      Body& b = body(w_.active_[p]);
      // With no static or sleeping body among its candidates (they come first) the
      // sweep has nothing to hit and the free motion stands: skip building its path.
      const std::uint32_t first = w_.first_candidate_[p];
      const bool near_fixed = first < w_.first_candidate_[p + 1] && w_.candidates_[first].fixed;
      for (int axis = first_axis; axis >= last_axis; --axis) {
        const double v_end = component(w_.step_velocity_[p], axis);
        const double x0 = component(b.position, axis);
        const double x_end = x0 + component(w_.step_displacement_[p], axis);
        if (!s_.continuous || !near_fixed) {
          component(b.position, axis) = x_end;
          component(b.velocity, axis) = v_end;
          continue;
        }
        const double a = component(moving_acceleration(b), axis);
        AxisPath path{
            s_.integrator, x0,   component(b.velocity, axis), a, component(b.friction, axis), h_,
            x_end,         v_end};
        sweep(p, b, axis, path);
        component(b.position, axis) = path.x1;
        component(b.velocity, axis) = path.v1;
      }
    }
  }

  void sweep(std::uint32_t p, Body& b, int axis, AxisPath& path) {
    for (int hit = 0; hit < kMaxHitsPerMove && path.x1 != path.x0; ++hit) {
      double first_t = kInfinity;
      double level = 0.0;
      double restitution = 0.0;
      std::uint32_t hit_body = kNone;
      std::uint32_t hit_candidate = kNone;
      for (std::uint32_t c = w_.first_candidate_[p]; c < w_.first_candidate_[p + 1]; ++c) {
        const Candidate& cand = w_.candidates_[c];
        if (!cand.fixed) break;  // fixed candidates come first
        const Body& o = body(cand.upper);
        component(b.position, axis) = path.x0;
        const auto span = overlap_interval(b, o, axis, 0.5 * s_.slop);
        if (!span || (path.x0 >= span->lo && path.x0 <= span->hi)) continue;
        const double target = path.x0 < span->lo ? span->lo : span->hi;
        const auto t = path.reaches(target);
        if (t && *t < first_t) {
          first_t = *t;
          level = target;
          restitution = mix_restitution(b.restitution, o.restitution);
          hit_body = cand.upper;
          hit_candidate = c;
        }
      }
      if (!(first_t < kInfinity)) return;
      ++w_.counters.swept_hits;
      // Bounce at the time of impact and spend the rest of the step going back.
      const double v_hit = path.velocity(first_t);
      // A sleeping body struck by a swept move wakes: harder than a resting contact
      // presses when struck from above, at all from the side, and from below
      // however slowly when the mover is driven into it (its acceleration, with
      // gravity and held support, points up at it) and would have gone in by more
      // than the slop: it would rest on a moving body (see separate()). A body of a
      // pile that rises a hair after a push is no such press; waking on it woke
      // whole columns of a sleeping pile, again and again.
      if (body(hit_body).is_dynamic()) {
        Vec2 travel{};
        component(travel, axis) = path.x0 > level ? -1.0 : 1.0;
        const double rising = dot(up_, travel);
        const bool driven = path.a * component(travel, axis) > 0.0;
        const bool from_below =
            gravity_on_ && rising > 0.0 && driven && std::fabs(path.x1 - level) > s_.slop;
        if (from_below || std::fabs(v_hit) > wake_speed(rising < 0.0)) {
          w_.to_wake_.push_back(hit_body);
        }
      }
      const double v_out =
          -effective_restitution(std::fabs(v_hit), restitution, rest_speed_) * v_hit;
      const double left = path.h - first_t;
      if (v_out == 0.0) {
        // Resting contact: stay where it touched, a few ulps inside so the contact
        // is surely found, and keep the approach velocity: the restitution phase
        // removes it with an impulse, which is what contact friction is bounded by.
        const double inside = path.x0 > level ? -kInfinity : kInfinity;
        double touching = level;
        for (int ulp = 0; ulp < 4; ++ulp) touching = std::nextafter(touching, inside);
        // The velocity kept is the free motion's at the end of the step: all that
        // acceleration pressed into the support over the step, not just until impact.
        const double pressed = (path.v1 > 0.0) == (v_hit > 0.0) ? path.v1 : v_hit;
        path = {path.integrator, touching, pressed, 0.0, 0.0, left, touching, pressed};
        // The contact is recorded here, with its true normal: on a curved surface
        // (a circle, a box's corner) the move on the other axis can leave the shapes
        // a hair apart, and a contact found only by overlap would then be missed,
        // the pressed velocity never removed, and the body would hang on the curve
        // gathering speed instead of sliding off it.
        component(b.position, axis) = touching;
        const Vec2 n = touching_normal(b, body(hit_body), axis, inside < 0.0 ? -1.0 : 1.0);
        record_contact(hit_candidate, n);
        return;
      }
      const AxisMotion rest =
          path.integrator == Integrator::Exact
              ? integrate_axis(Integrator::Exact, level, v_out, path.a, path.k, left)
              : AxisMotion{level + v_out * left, v_out};
      path = {path.integrator, level, v_out, path.a, path.k, left, rest.position, rest.velocity};
    }
  }

  // The unit normal from `mover` toward `obstacle` where they touch: the narrowphase
  // formulas' normal (line of centres, or a circle's centre to the nearest point of
  // a box), asked with a radius that always reaches; for two faces, along the swept
  // axis in the direction of travel (`toward`).
  static Vec2 touching_normal(const Body& mover, const Body& obstacle, int axis, double toward) {
    if (mover.shape == Shape::Circle && obstacle.shape == Shape::Circle) {
      return collide_circles(mover.position, kInfinity, obstacle.position, 0.0).normal;
    }
    if (mover.shape == Shape::Circle) {
      return collide_circle_box(mover.position, kInfinity, obstacle.bounds()).normal;
    }
    if (obstacle.shape == Shape::Circle) {
      return -collide_circle_box(obstacle.position, kInfinity, mover.bounds()).normal;
    }
    Vec2 along{};
    component(along, axis) = toward;
    return along;
  }

  // How close two bodies must be after the first pass to be worth another: within
  // the push margin of each other.
  double near_gap(const Body& a, const Body& b) const {
    return kPushMargin * std::min(std::min(a.half.x, a.half.y), std::min(b.half.x, b.half.y)) +
           s_.slop;
  }
  bool near(const Body& a, const Body& b) const {
    const double gap = near_gap(a, b);
    Aabb grown = a.bounds();
    grown.min -= Vec2{gap, gap};
    grown.max += Vec2{gap, gap};
    return boxes_intersect(grown, b.bounds());
  }

  // Gauss-Seidel passes over the candidate pairs: the first pass visits all of them
  // and keeps the pairs near enough to matter; later passes visit only those.
  // The passes come in two builds: with prefetching for bodies scattered in
  // memory, and without it, so that a stack's loop carries no trace of it.
  template <typename Resolve>
  void resolve_passes(Resolve&& resolve) {
    if (scattered_) {
      resolve_passes<true>(resolve);
    } else {
      resolve_passes<false>(resolve);
    }
  }

  template <bool kPrefetch, typename Resolve>
  void resolve_passes(Resolve& resolve) {
    auto& near_list = w_.near_candidates_;
    const auto candidates = static_cast<std::uint32_t>(w_.candidates_.size());
    near_list.resize(candidates);  // filled by index: no growth check per pair
    // The arrays by plain pointers: a push marks support through a byte store,
    // which may alias anything, and would make each pair reload them.
    std::uint32_t* const listed = near_list.data();
    const Candidate* const cands = w_.candidates_.data();
    Body* const bodies = w_.bodies.data();
    std::uint32_t near_count = 0;
    for (int iteration = 0; iteration < s_.position_iterations; ++iteration) {
      w_.supported_.assign(w_.active_.size(), 0);
      bool moved = false;
      if (iteration == 0) {
        for (std::uint32_t c = 0; c < candidates; ++c) {
          const Candidate& cand = cands[c];
          if (kPrefetch && c + kPrefetchAhead < candidates) {
            prefetch_pair(bodies, cands[c + kPrefetchAhead]);
          }
          Body& a = bodies[cand.lower];
          Body& b = bodies[cand.upper];
          if (!near(a, b)) continue;
          listed[near_count++] = c;
          moved = resolve(cand, a, b) || moved;
        }
      } else {
        for (std::uint32_t k = 0; k < near_count; ++k) {
          const Candidate& cand = cands[listed[k]];
          if (kPrefetch && k + kPrefetchAhead < near_count) {
            prefetch_pair(bodies, cands[listed[k + kPrefetchAhead]]);
          }
          moved = resolve(cand, bodies[cand.lower], bodies[cand.upper]) || moved;
        }
      }
      if (!moved) break;
    }
  }

  static void prefetch_pair(const Body* bodies, const Candidate& cand) {
    __builtin_prefetch(&bodies[cand.lower]);
    __builtin_prefetch(&bodies[cand.upper]);
  }

  // Per-axis resolution of box pairs: the lecture's penetration on the axis, pushed
  // apart by penetration plus slop, up if above, down if below. The axis is a
  // template argument: picking a component by a run-time axis cost a branch per
  // use, and the registers those branches tied up spilled the pair loop's state.
  template <int axis>
  void collide_boxes_on() {
    PhaseTimer t(s_.profile, w_.profile.narrowphase);
    constexpr int other = 1 - axis;
    const Vec2 unit = axis == 0 ? Vec2{1.0, 0.0} : Vec2{0.0, 1.0};
    std::uint64_t tests = 0;  // counted here, added once: the loop keeps it in a register
    resolve_passes([&](const Candidate& cand, Body& a, Body& b) {
      if (a.shape != Shape::Box || b.shape != Shape::Box) return false;
      ++tests;
      const Aabb ba = a.bounds();
      const Aabb bb = b.bounds();
      // Touching on the other axis only (side by side): that axis resolves it.
      const double across = std::min(component(ba.max, other), component(bb.max, other)) -
                            std::max(component(ba.min, other), component(bb.min, other));
      if (across <= 0.5 * s_.slop) return false;
      const double ca = component(a.position, axis);
      const double cb = component(b.position, axis);
      const Vec2 n = (cb >= ca) ? unit : -unit;  // from a toward b
      const double gap = std::min(component(ba.max, axis), component(bb.max, axis)) -
                         std::max(component(ba.min, axis), component(bb.min, axis));
      if (gap < 0.0) {  // apart on this axis: a near miss, or nothing
        // Two dynamic boxes side by side (across gravity) fall together and carry
        // nothing of each other: their near miss would only add work to a stack's
        // velocity pass (a third of it in the 5,050-box pyramid).
        const bool side_by_side = !cand.fixed && std::fabs(dot(n, up_)) < 1.0 - kAlongGravity;
        if (-gap <= near_miss_margin() && !side_by_side) record_near_miss(cand, n, -gap);
        return false;
      }
      const double depth =
          axis_penetration(ca, component(a.half, axis), cb, component(b.half, axis));
      // Resolve on this axis only if it is the shallower one. Otherwise a box that
      // sank a little into a floor tile would be thrown sideways by the tile's
      // width (catching on seams), or lifted by a neighbour's height.
      if (depth > across) return false;
      return separate(cand, a, b, n, depth);
    });
    w_.counters.box_box_tests += tests;
  }

  // The X phase: boxes on X, then every pair with a circle along its normal (a
  // circle's normal needs no axis split).
  void collide_on_x() {
    if (any_active_box_) collide_boxes_on<0>();
    if (!any_active_circle_ && !(any_active_box_ && w_.fixed_circles_ > 0)) return;
    PhaseTimer t(s_.profile, w_.profile.narrowphase);
    std::uint64_t circle_tests = 0;
    std::uint64_t mixed_tests = 0;
    // Shapes are tested grown by the near-miss margin: a pair a hair apart (as the
    // last push left it) is still a contact for the velocity pass. Circle pairs and
    // a circle facing a box's face are grown by the speculative margin too (see
    // speculative_margin_); a circle beside a box's corner is not: the corner of
    // the next tile of a floor is where a rolling circle would catch on a seam.
    const double margin = near_miss_margin();
    const double grown = margin + speculative_margin_;
    resolve_passes([&](const Candidate& cand, Body& a, Body& b) {
      Contact contact;
      bool corner = false;
      if (a.shape == Shape::Circle && b.shape == Shape::Circle) {
        ++circle_tests;
        contact = collide_circles(a.position, a.radius + grown, b.position, b.radius);
      } else if (a.shape == Shape::Circle) {
        ++mixed_tests;
        contact = collide_circle_box(a.position, a.radius + grown, b.bounds());
        corner = contact.normal.x != 0.0 && contact.normal.y != 0.0;
      } else if (b.shape == Shape::Circle) {
        ++mixed_tests;
        contact = collide_circle_box(b.position, b.radius + grown, a.bounds());
        contact.normal = -contact.normal;
        corner = contact.normal.x != 0.0 && contact.normal.y != 0.0;
      } else {
        return false;
      }
      if (!contact.colliding) return false;
      const double depth = contact.penetration - grown;
      if (depth < 0.0) {
        if (corner && -depth > margin) return false;
        record_near_miss(cand, contact.normal, -depth);
        return false;
      }
      return separate(cand, a, b, contact.normal, depth);
    });
    w_.counters.circle_circle_tests += circle_tests;
    w_.counters.circle_box_tests += mixed_tests;
  }

  // Shock propagation, for both the position and the velocity passes: a body resting
  // on support (a fixed body below it, or a supported body) is immovable for the
  // bodies it carries, for contacts within 72.5 degrees of vertical. wa and wb are
  // the inverse-mass weights of the pair; the carrier's becomes zero.
  void carry(bool fixed, std::uint32_t lower_pos, std::uint32_t upper_pos, double up, double& wa,
             double& wb) {
    carry(w_.supported_.data(), shock_, fixed, lower_pos, upper_pos, up, wa, wb);
  }
  // The same on a plain array: a loop that passes it keeps it in a register, where
  // the vector's pointer would be reloaded after every byte store (which may alias).
  static void carry(std::uint8_t* supported, bool shock, bool fixed, std::uint32_t lower_pos,
                    std::uint32_t upper_pos, double up, double& wa, double& wb) {
    if (fixed) {
      if (up < -kSupportCosine) supported[lower_pos] = 1;
    } else if (!shock) {
      return;
    } else if (up > kSupportCosine && supported[lower_pos]) {
      wa = 0.0;
      supported[upper_pos] = 1;
    } else if (up < -kSupportCosine && supported[upper_pos]) {
      wb = 0.0;
      supported[lower_pos] = 1;
    }
  }

  // Pushes a and b apart along n (from a toward b) by depth plus slop, split by
  // inverse mass, and records the contact for restitution. With shock propagation a
  // supported body is immovable for the bodies it carries.
  bool separate(const Candidate& cand, Body& a, Body& b, Vec2 n, double depth) {
    const double up = dot(n, up_);
    const auto c = static_cast<std::uint32_t>(&cand - w_.candidates_.data());
    double wa = a.inv_mass;
    double wb = cand.fixed ? 0.0 : b.inv_mass;
    carry(cand.fixed, cand.lower_pos, cand.upper_pos, up, wa, wb);
    const double sum = wa + wb;
    wa /= sum;
    wb /= sum;
    record_contact(c, n);
    // A sleeping body rests on sleeping ones only (update_sleep): one that an awake
    // body presses into from below, however slowly, rests on that body now, and
    // wakes (what rests on it wakes in turn as it moves).
    if (cand.fixed && gravity_on_ && up > 0.0 && depth > s_.slop && b.is_dynamic()) {
      w_.to_wake_.push_back(cand.upper);
    }
    const double push = depth + s_.slop;
    if (depth == 0.0 && !(push > 0.0)) return false;
    a.position -= n * (push * wa);
    b.position += n * (push * wb);
    if (any_contact_friction_ && a.contact_friction > 0.0 && b.contact_friction > 0.0) {
      hold_by_static_friction(cand, a, b, n, push, wa, wb);
    }
    // Only pushes against something immovable (a static or sleeping body, or a
    // supported one) may cancel velocity below; a push shared by two free bodies
    // is the restitution phase's to turn into equal and opposite impulses.
    if (wa == 1.0) a.correction -= n * push;
    if (wb == 1.0) b.correction += n * push;
    ++w_.counters.contacts;
    return depth > 0.0;
  }

  // Static friction in the position passes (as in position-based dynamics, Mueller
  // et al., "Detailed Rigid Body Simulation with Extended Position Based Dynamics"):
  // a push out along the normal turns the straight-down sink of a body resting on a
  // slope into a slide down it, a creep of g*h*h/2*sin(angle) every step that the
  // velocity pass cannot undo. When the pair's tangential displacement over the
  // sub-step is within the friction cone (at most mu times the push), it is undone:
  // a body on a slope no steeper than atan(mu) stays where it was.
  void hold_by_static_friction(const Candidate& cand, Body& a, Body& b, Vec2 n, double push,
                               double wa, double wb) {
    const Vec2 moved_a = a.position - w_.step_start_[cand.lower_pos];
    const Vec2 moved_b = cand.fixed ? Vec2{} : b.position - w_.step_start_[cand.upper_pos];
    const Vec2 relative = moved_b - moved_a;
    const Vec2 slide = relative - n * dot(relative, n);
    const double mu = mix_contact_friction(a.contact_friction, b.contact_friction) *
                      load_on(cand.fixed, a, b, dot(n, up_));
    if (!(length(slide) <= mu * push)) return;
    if (wa > 0.0 && !may_undo_slide(a, slide)) return;
    if (wb > 0.0 && !may_undo_slide(b, -slide)) return;
    a.position += slide * wa;
    b.position -= slide * wb;
    ++w_.counters.friction_holds;
  }

  // Whether the hold may move `body` along `undo`. The creep it is for goes the way
  // the body is driven (gravity and its own acceleration: downhill, under gravity
  // alone), so undoing it never moves a body further that way, and a body driven by
  // nothing has no creep to undo. Any other slide is a body escaping a squeeze: the
  // pushes of its other contacts lift it out of a pocket, or up a wall, because
  // nothing else can move. Undoing that left it at a fixed point deep inside its
  // neighbours, and the more friction the deeper: up to 0.096 m in hard case 6's
  // pile at friction 5 (docs/PHYSICS.md, "Squeezes at high friction").
  bool may_undo_slide(const Body& body, Vec2 undo) const {
    const Vec2 drive = driving_acceleration(body);
    if (drive.x == 0.0 && drive.y == 0.0) return false;
    return dot(undo, drive) <= 0.0;
  }

  // Two bodies at rest on each other are left a slop apart by the push that
  // separated them. If that pair were no contact in the next step, a column of
  // bodies falling together would have no contact inside it every other step: the
  // velocity pass would stop only its bottom, and the column would breathe by a
  // millimetre and 0.1 m/s a step forever, never asleep. Pairs closer than this
  // margin are resting contacts for the velocity pass, like touching ones (a gap
  // within the slop is closed by no velocity). Circles get a wider margin on top
  // (speculative_margin_).
  double near_miss_margin() const { return 2.0 * s_.slop; }

  // gap: how far apart the pair is (at most the margin it was found within).
  void record_near_miss(const Candidate& cand, Vec2 n, double gap) {
    // A near miss carries weight like a touching contact: the support marks pass
    // through it, or a body resting a slop above its support would not count as
    // supported, and what it carries would push it down into the pile.
    const double up = dot(n, up_);
    // A body already supported by a contact found before this one needs no second
    // support straight along gravity from a near miss (a box on two boxes rests on
    // either): half the contacts of a stack for the velocity pass, and the same
    // rest. A slanted one it keeps: a ball in a pocket needs both sides.
    const bool along_gravity = std::fabs(up) >= kAlongGravity;
    if (along_gravity && up > 0.0 && !cand.fixed && w_.supported_[cand.upper_pos]) return;
    if (along_gravity && up < 0.0 && w_.supported_[cand.lower_pos]) return;
    double wa = 1.0;
    double wb = 1.0;
    carry(cand.fixed, cand.lower_pos, cand.upper_pos, up, wa, wb);
    // It is a contact only while the pair rests on each other, approaching no faster
    // than the rest speed: a faster approach is a collision, which the next step
    // finds as an overlap and bounces.
    const Vec2 vb = cand.fixed ? Vec2{} : body(cand.upper).velocity;
    if (dot(vb - body(cand.lower).velocity, n) < -rest_speed_) return;
    const auto c = static_cast<std::uint32_t>(&cand - w_.candidates_.data());
    if (w_.contact_of_candidate_[c] != kNone && !w_.contact_near_miss_[c]) return;
    record_contact(c, n);
    w_.contact_near_miss_[c] = 1;
    w_.contact_gap_[c] = gap;
  }

  // Marks candidate c as a contact with normal n; the restitution phase gathers
  // the marked candidates in candidate order (so no sort is needed).
  void record_contact(std::uint32_t c, Vec2 n) {
    w_.contact_of_candidate_[c] = 1;
    w_.contact_near_miss_[c] = 0;
    w_.contact_normal_[c] = n;
  }

  // The velocity component along each contact's normal is reflected and scaled by
  // the restitution (zeroed below the rest speed), impulses split by inverse mass.
  void restitution() {
    // Records are written in place: the array only grows (no clearing, no growth
    // check per contact), contact_count_ says how many are this sub-step's.
    if (w_.contacts_.size() < w_.candidates_.size()) w_.contacts_.resize(w_.candidates_.size());
    contact_count_ = 0;
    // Without friction, the iterations run two contacts at a time, with the same
    // results (ContactLanes). Shock propagation's weights for them are found as the
    // contacts are gathered, in the same order.
    lanes_ = kHaveContactLanes && !any_contact_friction_;
    if (lanes_) {
      if (w_.contact_weights_.size() < w_.candidates_.size()) {
        w_.contact_weights_.resize(w_.candidates_.size());
      }
      w_.supported_.assign(w_.active_.size(), 0);
    }
    // Gather the marked candidates in candidate order, with what the iterations read.
    // Candidates come grouped by their lower body's position p, and a body is never
    // read again once its group is done (later groups hold only higher bodies), so
    // its velocity is cancelled into its corrections right there, while it is in
    // cache. With no contact at all every correction is zero and that changes nothing.
    const double per_second = 1.0 / h_;
    const auto active = static_cast<std::uint32_t>(w_.active_.size());
    const auto candidate_count = static_cast<std::uint32_t>(w_.candidates_.size());
    // The iterations read and write only awake bodies' velocities (a fixed body's
    // counts as zero): they work on a dense copy by position, written back at the end.
    // One velocity more, always zero: what a fixed body's lane reads (ContactLanes).
    auto& velocity = w_.solver_velocity_;
    velocity.resize(active + 1);
    velocity[active] = {};
    if (hold_) {  // what the contacts will do along "up" is measured from here
      w_.velocity_before_contacts_.resize(active);
      w_.in_contact_.assign(active, 0);
    }
    for (std::uint32_t p = 0; p < active; ++p) {
      if (scattered_) prefetch_ahead(p);
      for (std::uint32_t c = w_.first_candidate_[p]; c < w_.first_candidate_[p + 1]; ++c) {
        // The upper bodies are anywhere in memory, as the lower ones are.
        if (scattered_ && c + kPrefetchAhead < candidate_count) {
          __builtin_prefetch(&w_.bodies[w_.candidates_[c + kPrefetchAhead].upper]);
        }
        if (w_.contact_of_candidate_[c] != kNone) gather_contact(c);
      }
      // Cancelled in a register and stored whole: reading back a velocity just
      // stored one half at a time stalls the load.
      Body& b = body(w_.active_[p]);
      if (hold_) w_.velocity_before_contacts_[p] = b.velocity;
      const Vec2 v = cancelled_velocity(b.velocity, b.correction, per_second);
      b.velocity = v;
      velocity[p] = v;
    }
    if (contact_count_ == 0) {  // no contact holds anything
      if (hold_) update_held();
      return;
    }
    ++w_.counters.restitution_passes;
    const std::span<ContactRecord> contacts(w_.contacts_.data(), contact_count_);
    Vec2* const solver = velocity.data();
    const bool shock = shock_;
    if (lanes_) {
      const std::span<const ContactWeights> weights(w_.contact_weights_.data(), contact_count_);
      w_.contact_lanes_.pack(contacts, weights, active);
    }
    for (int iteration = 0; iteration < s_.velocity_iterations; ++iteration) {
      bool changed = false;
      if (lanes_) {
        changed = w_.contact_lanes_.iterate(solver, iteration == 0);
      } else {
        w_.supported_.assign(w_.active_.size(), 0);
        std::uint8_t* const supported = w_.supported_.data();
        if (any_contact_friction_) {
          solve_contacts<true>(contacts, solver, supported, shock, iteration == 0, changed);
        } else {
          solve_contacts<false>(contacts, solver, supported, shock, iteration == 0, changed);
        }
      }
      if (!changed && iteration > 0) break;
    }
    if (lanes_) w_.contact_lanes_.unpack(contacts);
    // The velocities go back to the bodies; what the contacts held of each one's
    // acceleration is found in the same walk (update_held's, while the body is in cache).
    for (std::uint32_t p = 0; p < active; ++p) {
      if (scattered_) prefetch_ahead(p);
      Body& b = body(w_.active_[p]);
      b.velocity = velocity[p];
      if (hold_) update_held(p, b);
    }
    if (s_.warm_starting) remember_impulses();
    if (shock_ && any_contact_friction_) update_loads(contacts);
  }

  // One iteration over the contacts. Built apart for scenes with contact friction
  // and without (kFriction): without it, no contact has friction to apply.
  template <bool kFriction>
  static void solve_contacts(std::span<ContactRecord> contacts, Vec2* solver,
                             std::uint8_t* supported, bool shock, bool first_iteration,
                             bool& changed) {
    for (ContactRecord& k : contacts) {
      if (k.fixed) {
        solve_contact<true, kFriction>(k, solver, supported, shock, first_iteration, changed);
      } else {
        solve_contact<false, kFriction>(k, solver, supported, shock, first_iteration, changed);
      }
    }
  }

  // One contact in one iteration of the restitution phase, built apart for contacts
  // with a fixed body (no velocity of its own) and between two awake bodies, so
  // that neither carries the other's tests.
  template <bool kFixed, bool kFriction>
  static void solve_contact(ContactRecord& k, Vec2* solver, std::uint8_t* supported, bool shock,
                            bool first_iteration, bool& changed) {
    Vec2 fixed_velocity{};  // what vb names for a fixed body; never read
    Vec2& va = solver[k.lower_pos];
    Vec2& vb = kFixed ? fixed_velocity : solver[k.upper_pos];
    const Vec2 n = k.normal;
    double wa = k.inv_mass_lower;
    double wb = k.inv_mass_upper;
    carry(supported, shock, kFixed, k.lower_pos, k.upper_pos, k.up, wa, wb);
    // The pair's effective mass, once for the normal and the friction impulse.
    const double mass = 1.0 / (wa + wb);
    double closing = dot((kFixed ? Vec2{} : vb) - va, n);
    // An immovable supporter can stop the bodies it carries but never lift them:
    // its own motion away from them counts as zero. Otherwise a supported body
    // moving up hands its velocity to every body above it, all the way up a pile.
    if (wa == 0.0 && !kFixed) closing += std::max(dot(va, n), 0.0);
    if (wb == 0.0 && !kFixed) closing -= std::min(dot(vb, n), 0.0);
    if (wa + wb <= 0.0) return;
    // Sequential impulses: the impulse accumulated on a contact may shrink again
    // but never pull (stay >= 0), so iterations converge to a velocity that
    // neither approaches nor separates from resting contacts.
    double& total = k.impulse;
    if (first_iteration && k.warm > 0.0) {
      // Warm start: begin from last step's impulse on this pair, so resting
      // contacts converge over steps instead of within one.
      total = k.warm;
      va -= n * (total * wa);
      if (!kFixed) vb += n * (total * wb);
      changed = true;
      if (k.mu > 0.0) {
        // Friction warm-starts too, within the cone of the warm normal impulse
        // (Box2D's warm start of the tangent impulse): a pile holds its
        // sideways loads through chains of friction that a few iterations from
        // zero would not rebuild every step.
        const Vec2 t{-n.y, n.x};
        const double limit = k.mu * total;
        k.tangent_impulse = std::clamp(k.warm_tangent, -limit, limit);
        va -= t * (k.tangent_impulse * wa);
        if (!kFixed) vb += t * (k.tangent_impulse * wb);
        apply_contact_friction<kFixed>(k, va, vb, wa, wb, mass);
      }
      return;
    }
    // Without friction, no branch on whether the impulse clamps or changes: in a
    // flowing pile either is a coin toss per contact (a zero impulse changes no
    // velocity's value), and resolve is 21% faster so. With friction, where
    // contacts hold and their impulses settle, the branches won (by 4.6%).
    const double unclamped = total + (k.target - closing) * mass;
    const double wanted = kFriction ? std::max(unclamped, 0.0) : at_least_zero(unclamped);
    const double impulse = wanted - total;
    if (!kFriction || impulse != 0.0) {
      total = wanted;
      va -= n * (impulse * wa);
      if (!kFixed) vb += n * (impulse * wb);
      changed = changed | (std::fabs(impulse) > 1.0e-12);
    }
    if (kFriction && k.mu > 0.0) {
      changed = apply_contact_friction<kFixed>(k, va, vb, wa, wb, mass) || changed;
    }
  }

  // One marked candidate as a contact record (targets from the velocities before
  // any impulse or cancellation of this phase).
  void gather_contact(std::uint32_t c) {
    const Candidate& cand = w_.candidates_[c];
    const Body& a = body(cand.lower);
    const Body& b = body(cand.upper);
    ContactRecord& k = w_.contacts_[contact_count_++];
    k.lower = cand.lower;
    k.upper = cand.upper;
    k.lower_pos = cand.lower_pos;
    k.upper_pos = cand.upper_pos;
    k.normal = w_.contact_normal_[c];
    k.up = dot(k.normal, up_);
    k.inv_mass_lower = a.inv_mass;
    k.inv_mass_upper = cand.fixed ? 0.0 : b.inv_mass;
    const double closing = dot(b.velocity - a.velocity, k.normal);
    const double e = mix_restitution(a.restitution, b.restitution);
    k.target = closing < 0.0 ? -effective_restitution(-closing, e, rest_speed_) * closing : 0.0;
    // A near miss is a speculative contact: the pair may close its gap (down to
    // the slop it keeps) within this sub-step, and no more.
    if (w_.contact_near_miss_[c])
      k.target = -std::max(w_.contact_gap_[c] - near_miss_margin(), 0.0) / h_;
    k.mu = mix_contact_friction(a.contact_friction, b.contact_friction) *
           load_on(cand.fixed, a, b, k.up);
    const WarmEntry* warm =
        s_.warm_starting ? w_.warm_entry(cand.lower, cand.upper, b.generation) : nullptr;
    k.warm = warm != nullptr ? warm->impulse : 0.0;
    k.warm_tangent = warm != nullptr ? warm->tangent_impulse : 0.0;
    k.impulse = 0.0;
    k.tangent_impulse = 0.0;
    k.upper_generation = b.generation;
    k.fixed = cand.fixed;
    if (cand.fixed && b.is_dynamic()) wake_if_hit(cand, k, closing);
    if (lanes_) {
      // Shock propagation's weights depend on the contacts' angles and order alone,
      // so every iteration would find the same: the lanes take them from here.
      double wa = k.inv_mass_lower;
      double wb = k.inv_mass_upper;
      carry(cand.fixed, cand.lower_pos, cand.upper_pos, k.up, wa, wb);
      w_.contact_weights_[contact_count_ - 1] = {wa, wb};
    }
    if (hold_) {
      w_.in_contact_[cand.lower_pos] = 1;
      if (!cand.fixed) w_.in_contact_[cand.upper_pos] = 1;
    }
  }

  // Coulomb friction: the tangential impulse accumulated on a contact stays within
  // mu times its normal impulse (a contact that pushes nothing holds nothing).
  template <bool kFixed>
  static bool apply_contact_friction(ContactRecord& k, Vec2& va, Vec2& vb, double wa, double wb,
                                     double mass) {
    const Vec2 n = k.normal;
    const Vec2 t{-n.y, n.x};
    const double sliding = dot((kFixed ? Vec2{} : vb) - va, t);
    const double limit = k.mu * k.impulse;
    double& total = k.tangent_impulse;
    const double wanted = std::clamp(total - sliding * mass, -limit, limit);
    const double impulse = wanted - total;
    if (impulse == 0.0) return false;
    total = wanted;
    va -= t * (impulse * wa);
    if (!kFixed) vb += t * (impulse * wb);
    return std::fabs(impulse) > 1.0e-12;
  }

  // The load factor of a contact's friction: for a support contact (within 72.5
  // degrees of vertical), the load of the body on top; 1 for any other.
  static double load_on(bool fixed, const Body& lower, const Body& upper, double up) {
    if (up < -kSupportCosine) return lower.load;
    if (up > kSupportCosine && !fixed) return upper.load;
    return 1.0;
  }

  // Shock propagation makes a supported body immovable for what rests on it, so its
  // own contacts below push up only its own weight: the weight of the pile above it
  // never reaches them, and friction, bounded by the push, holds it as if nothing
  // rested on it. Bodies deep in a pile are then pushed aside by their neighbours
  // and the pile creeps down. So the load is put back, for friction only: from the
  // top of the pile down, each body's supports carry its own push plus what rests
  // on it, shared among them as they share its own push, and its load factor
  // (Body::load) is that total over its own. Contacts are grouped by their lower
  // body's position in the processing order (bottom up), so one walk from the end
  // meets every body's load from above before its own supports.
  void update_loads(std::span<const ContactRecord> contacts) {
    const std::size_t n = w_.active_.size();
    auto& own = w_.support_impulse_;
    auto& carried = w_.carried_impulse_;
    own.assign(n, 0.0);
    carried.assign(n, 0.0);
    for (const ContactRecord& k : contacts) {
      if (k.up < -kSupportCosine) own[k.lower_pos] -= k.impulse * k.up;
      if (k.up > kSupportCosine && !k.fixed) own[k.upper_pos] += k.impulse * k.up;
    }
    // A body whose supports pushed less than its weight (landing, or held by the
    // position passes) shares what it carries as if they had pushed its weight.
    const double weight = length(s_.gravity) * h_;  // a body's own push, per unit mass
    const auto factor = [&](std::uint32_t p) {
      const double resting = std::max(own[p], body(w_.active_[p]).mass * weight);
      return std::max(1.0, (own[p] + carried[p]) / resting);
    };
    for (std::size_t i = contacts.size(); i-- > 0;) {
      const ContactRecord& k = contacts[i];
      if (k.fixed) continue;  // a static or sleeping body passes nothing on
      if (k.up > kSupportCosine) {
        carried[k.lower_pos] += k.impulse * k.up * factor(k.upper_pos);
      } else if (k.up < -kSupportCosine) {
        carried[k.upper_pos] -= k.impulse * k.up * factor(k.lower_pos);
      }
    }
    for (std::uint32_t p = 0; p < n; ++p) {
      if (scattered_) prefetch_ahead(p);
      body(w_.active_[p]).load = factor(p);
    }
  }

  // What the contacts did to a body's velocity this sub-step, per axis, is how
  // much of its acceleration (gravity and its own) they held; the next sub-step
  // applies it as a force from the start (the support and friction a resting body
  // will get again). Only for a body that is resting after its contacts (no faster
  // than the rest speed): an impact is no support. Per axis between 0 and the
  // acceleration: contacts hold a body back, never pull it, and never hold it back
  // harder than it is pushed.
  void update_held() {
    for (std::size_t p = 0; p < w_.active_.size(); ++p) {
      if (scattered_) prefetch_ahead(p);
      update_held(p, body(w_.active_[p]));
    }
  }
  void update_held(std::size_t p, Body& b) const {
    if (!w_.in_contact_[p] || dot(b.velocity, b.velocity) > rest_speed_ * rest_speed_) {
      b.held = {};
      return;
    }
    const Vec2 a = driving_acceleration(b);  // hold_: gravity is on
    const Vec2 change = b.velocity - w_.velocity_before_contacts_[p];
    b.held = {held_part(change.x / h_, a.x), held_part(change.y / h_, a.y)};
  }
  // The part of a velocity change (per second) that held back an acceleration a.
  static double held_part(double change, double a) {
    return a < 0.0 ? std::clamp(change, 0.0, -a) : std::clamp(change, -a, 0.0);
  }

  // Each awake body keeps the impulses of the contacts it was the lower body of.
  void remember_impulses() {
    // Contacts come grouped by the lower body's position: one walk rewrites the
    // pool in processing order.
    const std::span<const ContactRecord> contacts(w_.contacts_.data(), contact_count_);
    auto& pool = w_.warm_pool;
    pool.clear();
    std::size_t i = 0;
    for (std::uint32_t p = 0; p < w_.active_.size(); ++p) {
      const std::uint32_t slot = w_.active_[p];
      const auto first = static_cast<std::uint32_t>(pool.size());
      std::uint8_t count = 0;
      for (; i < contacts.size() && contacts[i].lower_pos == p; ++i) {
        const ContactRecord& k = contacts[i];
        if (!(k.impulse <= 0.0) && count < kWarmSlots) {
          pool.push_back({k.upper, k.upper_generation, k.impulse, k.tangent_impulse});
          ++count;
        }
      }
      w_.warm_first[slot] = first;
      w_.warm_count[slot] = count;
    }
  }

  // A body pushed back out of a penetration by something immovable loses the
  // velocity that drove it in, up to correction / h, but gains none along the push. Without this a
  // body jammed against others (a row pressed to a wall) keeps the velocity the
  // contact iterations could not remove: it is put back in place every step while
  // its velocity grows, and the pile never comes to rest.
  static Vec2 cancelled_velocity(Vec2 v, Vec2 correction, double per_second) {
    // Per axis, so that a push up from a floor cannot turn into sideways motion.
    for (int axis = 0; axis < 2; ++axis) {
      const double pushed = component(correction, axis);
      double& u = component(v, axis);
      if (pushed > 0.0 && u < 0.0) u = std::min(0.0, u + pushed * per_second);
      if (pushed < 0.0 && u > 0.0) u = std::max(0.0, u + pushed * per_second);
    }
    return v;
  }

  // A sleeping body wakes when it is hit: harder than a resting contact presses
  // (from above), or at all from the side or below. From above means any contact
  // on its upper side, a steep one too: a body resting there closes on it by up to
  // the g*h it gained in the sub-step, which is no hit.
  void wake_if_hit(const Candidate& cand, const ContactRecord& contact, double closing) {
    const bool resting_on_it = contact.up < 0.0;
    if (-closing > wake_speed(resting_on_it)) w_.to_wake_.push_back(cand.upper);
  }
  double wake_speed(bool resting_on_it) const {
    return resting_on_it ? rest_speed_ : s_.sleep_speed;
  }

  void hold_in_bounds() {
    if (!s_.has_bounds) return;
    for (std::uint32_t slot : w_.active_) {
      Body& b = body(slot);
      bool clamped = false;
      for (int axis = 0; axis < 2; ++axis) {
        const double lo = component(s_.bounds.min, axis) + component(b.half, axis);
        const double hi = component(s_.bounds.max, axis) - component(b.half, axis);
        double& x = component(b.position, axis);
        double& v = component(b.velocity, axis);
        if (x < lo) {
          x = std::min(lo, hi);
          v = std::max(v, 0.0);
          clamped = true;
        } else if (x > hi) {
          x = std::max(hi, lo);
          v = std::min(v, 0.0);
          clamped = true;
        }
      }
      if (clamped) ++w_.counters.bounds_clamps;
    }
  }

  // A body that has been still for sleep_time is ready to sleep. Bodies near each
  // other form an island (union-find over this sub-step's candidate pairs, static
  // and sleeping bodies not linking), and an island sleeps when all of it is ready,
  // or from the bottom up as far as it is (sleep_from_the_bottom).
  void update_sleep() {
    for (std::uint32_t slot : w_.to_wake_) w_.wake(slot);
    w_.to_wake_.clear();
    if (!s_.sleeping) return;
    const std::size_t n = w_.active_.size();
    bool any_ready = false;
    // "Still" is judged over the window, not by the speed of one step: a body of a
    // pile jitters by rounding-sized pushes at any instant, but a body at rest stays
    // within sleep_speed * sleep_time of where the window began.
    const double radius = s_.sleep_speed * s_.sleep_time;
    // Whether each body is ready is kept by position: the walks below read it there
    // instead of from the body's cold cache line, all over memory.
    auto& ready = w_.still_ready_;
    ready.resize(n);
    for (std::uint32_t p = 0; p < n; ++p) {
      if (scattered_) prefetch_ahead_with_cold_line(p);
      Body& b = body(w_.active_[p]);
      if (length(b.position - b.still_anchor) > radius) {
        b.still_anchor = b.position;
        b.still_time = 0.0;
      } else {
        b.still_time += h_;
      }
      ready[p] = static_cast<std::uint8_t>(b.still_time >= s_.sleep_time);
      any_ready = any_ready || ready[p] != 0;
    }
    if (!any_ready) return;

    auto& parent = w_.island_parent_;
    parent.resize(n);
    for (std::uint32_t p = 0; p < n; ++p) parent[p] = p;
    const auto root = [&parent](std::uint32_t p) {
      while (parent[p] != p) p = parent[p] = parent[parent[p]];
      return p;
    };
    // Islands link through candidate pairs, not only touching ones: neighbours a
    // slop apart in a pile are one island, so no part of a pile sleeps alone.
    for (const Candidate& cand : w_.candidates_) {
      if (cand.fixed) continue;
      const std::uint32_t a = root(cand.lower_pos);
      const std::uint32_t b = root(cand.upper_pos);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
    auto& island_ready = w_.sleep_ready_;
    island_ready.assign(n, 1);
    for (std::uint32_t p = 0; p < n; ++p) {
      if (!ready[p]) island_ready[root(p)] = 0;
    }
    auto& asleep = w_.goes_to_sleep_;
    asleep.resize(n);
    for (std::uint32_t p = 0; p < n; ++p) asleep[p] = island_ready[root(p)];
    if (gravity_on_) sleep_from_the_bottom(asleep);  // no "below" without gravity
    for (std::uint32_t p = 0; p < n; ++p) {
      if (!asleep[p]) continue;
      Body& b = body(w_.active_[p]);
      b.awake = false;
      b.velocity = {};
      b.held = {};
      b.load = 1.0;
      w_.fell_asleep(w_.active_[p]);
    }
  }

  // An island sleeps as a whole when all of it is ready; in one that is not, a
  // ready body still sleeps when it rests only on what is asleep or static: it has
  // a contact below it (one whose normal has any component along "up", a steep
  // one of an arch too), and every body below it that it touches is asleep. Bodies
  // come from the lowest up, so a still pile falls asleep from the floor up to
  // where something still moves, in one pass; what rests on a moving body stays
  // awake. A sleeping body is as immovable for what it carries as shock
  // propagation already makes a supported one, so the bodies above see no change;
  // without this, one avalanche anywhere in a pile of 16,000 kept all of it awake.
  void sleep_from_the_bottom(std::vector<std::uint8_t>& asleep) {
    const std::span<const ContactRecord> contacts(w_.contacts_.data(), contact_count_);
    const std::size_t n = w_.active_.size();
    auto& first = w_.first_support_;
    auto& supporters = w_.supporters_;
    auto& cursor = w_.support_cursor_;
    // Each contact with a vertical component: the awake body on top (kNone when
    // that is the fixed one, which needs no support) and the one under it.
    struct Link {
      std::uint32_t carried;
      std::uint32_t supporter;  // kNone when static or sleeping
    };
    const auto link_of = [](const ContactRecord& k) {
      if (k.up > 0.0) return Link{k.fixed ? kNone : k.upper_pos, k.lower_pos};
      if (k.up < 0.0) return Link{k.lower_pos, k.fixed ? kNone : k.upper_pos};
      return Link{kNone, kNone};
    };
    first.assign(n + 1, 0);
    for (const ContactRecord& k : contacts) {
      const Link link = link_of(k);
      if (link.carried != kNone) ++first[link.carried + 1];
    }
    for (std::size_t p = 0; p < n; ++p) first[p + 1] += first[p];
    supporters.resize(first[n]);
    cursor.assign(first.begin(), first.end() - 1);
    for (const ContactRecord& k : contacts) {
      const Link link = link_of(k);
      if (link.carried != kNone) supporters[cursor[link.carried]++] = link.supporter;
    }
    for (std::uint32_t p = 0; p < n; ++p) {
      if (asleep[p] || first[p] == first[p + 1]) continue;
      if (!w_.still_ready_[p]) continue;
      // A supporter later in the order (level with p, within the slop) is not judged
      // yet: p waits for the next sub-step.
      const auto on_sleeper = [&](std::uint32_t q) { return q == kNone || asleep[q] != 0; };
      if (std::all_of(supporters.begin() + first[p], supporters.begin() + first[p + 1],
                      on_sleeper)) {
        asleep[p] = 1;
      }
    }
    sleep_held_groups(contacts, asleep);
  }

  // The pass above never sleeps a body with no contact below it: one wedged between
  // its neighbours and held up by their friction (a keystone), still for seconds.
  // Nor, then, the neighbours resting on it, nor anything above them: in a pile of
  // 16,000 with friction, 7,000 still bodies stayed awake for ever over a handful
  // of keystones. So still bodies left awake sleep together, as a group, when
  // whatever holds any of them is asleep, static or in the group: a body's holders
  // are the bodies below it that it touches, or, with none below, every body it
  // touches. A still body held by a moving one is blocked, and so is every body
  // it holds, and so on (a walk over the holders, cycles and all). Of the rest, a
  // body sleeps if its holders lead down to a static or sleeping body (grounded):
  // a group held by nothing asleep is not at rest on anything.
  void sleep_held_groups(std::span<const ContactRecord> contacts,
                         std::vector<std::uint8_t>& asleep) {
    const std::size_t n = w_.active_.size();
    auto& state = w_.held_state_;  // per position: kCandidate, kBlocked, kGrounded, or 0
    state.assign(n, 0);
    bool any = false;
    for (std::uint32_t p = 0; p < n; ++p) {
      if (!asleep[p] && w_.still_ready_[p]) {
        state[p] = kCandidate;
        any = true;
      }
    }
    if (!any) return;
    const auto& first = w_.first_support_;
    const auto has_support = [&first](std::uint32_t p) { return first[p] != first[p + 1]; };
    // (held, holder) pairs, holder kNone when static or sleeping.
    auto& holds = w_.holds_;
    holds.clear();
    const auto add = [&](std::uint32_t held, std::uint32_t holder) {
      if (state[held] != kCandidate) return;
      holds.push_back({held, holder != kNone && asleep[holder] ? kNone : holder});
    };
    for (const ContactRecord& k : contacts) {
      const std::uint32_t lower = k.lower_pos;
      const std::uint32_t upper = k.fixed ? kNone : k.upper_pos;
      // The support links of sleep_from_the_bottom, and every contact of a body
      // with none.
      if (k.up < 0.0 || !has_support(lower)) add(lower, upper);
      if (upper != kNone && (k.up > 0.0 || !has_support(upper))) add(upper, lower);
    }
    // Who each awake body holds, for the walks (CSR by holder).
    auto& start = w_.held_start_;
    auto& held_by = w_.held_list_;
    start.assign(n + 1, 0);
    for (const auto& h : holds) {
      if (h.second != kNone) ++start[h.second + 1];
    }
    for (std::size_t p = 0; p < n; ++p) start[p + 1] += start[p];
    held_by.resize(start[n]);
    auto& cursor = w_.support_cursor_;
    cursor.assign(start.begin(), start.end() - 1);
    for (const auto& h : holds) {
      if (h.second != kNone) held_by[cursor[h.second]++] = h.first;
    }
    // Blocked: held by a moving body, or by a blocked one.
    auto& work = w_.held_work_;
    work.clear();
    for (const auto& h : holds) {
      if (h.second != kNone && state[h.second] == 0 && state[h.first] == kCandidate) {
        state[h.first] = kBlocked;
        work.push_back(h.first);
      }
    }
    const auto spread = [&](std::uint8_t from, std::uint8_t to) {
      while (!work.empty()) {
        const std::uint32_t q = work.back();
        work.pop_back();
        for (std::uint32_t i = start[q]; i < start[q + 1]; ++i) {
          const std::uint32_t p = held_by[i];
          if (state[p] == from) {
            state[p] = to;
            work.push_back(p);
          }
        }
      }
    };
    spread(kCandidate, kBlocked);
    // Grounded: held by a static or sleeping body, or by a grounded one.
    for (const auto& h : holds) {
      if (h.second == kNone && state[h.first] == kCandidate) {
        state[h.first] = kGrounded;
        work.push_back(h.first);
      }
    }
    spread(kCandidate, kGrounded);
    for (std::uint32_t p = 0; p < n; ++p) {
      if (state[p] == kGrounded) asleep[p] = 1;
    }
  }
  static constexpr std::uint8_t kCandidate = 1;
  static constexpr std::uint8_t kBlocked = 2;
  static constexpr std::uint8_t kGrounded = 3;

  WorldImpl& w_;
  const WorldSettings& s_;
  double h_;
  bool gravity_on_;
  Vec2 up_;
  double rest_speed_;
  bool shock_;
  bool hold_;
  // A support a little below a resting body is no contact for the velocity pass
  // beyond the near-miss margin, so shock propagation's marks stop there: in a deep
  // pile, whatever rests above such a gap (a column of 60 circles along a wall)
  // fell freely for steps and was pushed back up by centimetres, never asleep.
  // Gaps up to half what a body falls from rest in one sub-step (g*h*h/2, 1.4 mm
  // at 60 Hz) are speculative contacts instead (Box2D v3's speculative distance),
  // closing at most their gap in a sub-step. Zero without gravity.
  double speculative_margin_;
  bool any_active_box_ = false;
  bool any_active_circle_ = false;
  bool any_contact_friction_ = false;
  bool lanes_ = false;               // this sub-step's velocity iterations run in ContactLanes
  bool order_changed_ = false;       // set by order_by_height()
  bool scattered_ = false;           // the processing order is far from slot order
  bool all_inside_ = false;          // integrate() found every body inside its fat box
  bool fat_made_ = false;            // integrate() made the new fat boxes (next_fat_boxes_)
  std::uint32_t contact_count_ = 0;  // records in use at the front of contacts_
  double surely_slow_;               // squared speeds at or below this are under max_speed
};

void WorldImpl::step(double dt) {
  const auto start = std::chrono::steady_clock::now();
  profile = {};
  const double h = dt / settings.substeps;
  for (int i = 0; i < settings.substeps; ++i) {
    StepRunner(*this, h).run();
    ++counters.substeps;
  }
  ++steps;
  ++counters.steps;
  if (settings.profile) {
    profile.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
}

}  // namespace phys
