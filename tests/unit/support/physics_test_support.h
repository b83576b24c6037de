#pragma once
// Helpers shared by the unit and stability suites: body definitions with short
// names, a world fixture (make_box, make_circle, step_n), and measurements that do
// not reuse the core's own collision formulas nor its broadphase (overlap depth and
// the pairs it is measured on, kinetic energy), so a wrong core formula or a grid
// that misses pairs cannot hide behind an equally wrong measurement.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <compare>
#include <cstdint>
#include <string>
#include <vector>

#include "physics/body.h"
#include "physics/settings.h"
#include "physics/vec2.h"
#include "physics/world.h"

namespace phys::testing {

// A parameterized test's name may hold only letters, digits and underscores.
inline std::string test_name(std::string name) {
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

// The server's tick: 60 Hz.
inline constexpr double kDt = 1.0 / 60.0;

inline BodyDef box_def(Vec2 center, Vec2 half_extents, Motion motion = Motion::Dynamic) {
  BodyDef def;
  def.shape = Shape::Box;
  def.motion = motion;
  def.position = center;
  def.half_extents = half_extents;
  return def;
}

inline BodyDef circle_def(Vec2 center, double radius, Motion motion = Motion::Dynamic) {
  BodyDef def;
  def.shape = Shape::Circle;
  def.motion = motion;
  def.position = center;
  def.radius = radius;
  return def;
}

// Adds a body that the test expects to be accepted; a refusal fails the test.
inline BodyId add_or_fail(World& world, const BodyDef& def) {
  BodyDefError error = BodyDefError::None;
  const BodyId id = world.add_body(def, &error);
  EXPECT_TRUE(id.is_valid()) << "body refused: " << describe(error);
  return id;
}

inline Aabb aabb_of(const BodyState& body) {
  if (body.shape == Shape::Circle) {
    const Vec2 r{body.radius, body.radius};
    return {body.position - r, body.position + r};
  }
  return {body.position - body.half_extents, body.position + body.half_extents};
}

// How deep two bodies overlap (> 0), or how far apart they are (<= 0), computed
// here from the shapes, independently of the core's narrowphase.
inline double overlap_depth(const BodyState& a, const BodyState& b) {
  if (a.shape == Shape::Box && b.shape == Shape::Box) {
    const double ox = a.half_extents.x + b.half_extents.x - std::abs(a.position.x - b.position.x);
    const double oy = a.half_extents.y + b.half_extents.y - std::abs(a.position.y - b.position.y);
    return std::min(ox, oy);
  }
  if (a.shape == Shape::Circle && b.shape == Shape::Circle) {
    return a.radius + b.radius - length(a.position - b.position);
  }
  const BodyState& circle = a.shape == Shape::Circle ? a : b;
  const BodyState& box = a.shape == Shape::Circle ? b : a;
  const Vec2 lo = box.position - box.half_extents;
  const Vec2 hi = box.position + box.half_extents;
  const Vec2 c = circle.position;
  const bool inside = c.x > lo.x && c.x < hi.x && c.y > lo.y && c.y < hi.y;
  if (inside) {
    const double to_face = std::min({c.x - lo.x, hi.x - c.x, c.y - lo.y, hi.y - c.y});
    return circle.radius + to_face;
  }
  const Vec2 closest{std::clamp(c.x, lo.x, hi.x), std::clamp(c.y, lo.y, hi.y)};
  return circle.radius - length(c - closest);
}

// Two indices into a list of boxes, a < b.
struct IndexPair {
  std::uint32_t a;
  std::uint32_t b;
  constexpr auto operator<=>(const IndexPair&) const = default;
};

// Every pair of boxes that overlap or touch, found here by sort and sweep on x
// rather than by the core's grid, so that a grid that misses pairs cannot hide the
// overlaps it causes: the boxes in order of their left edges, each paired with
// those after it whose left edge is not right of its right edge and whose y ranges
// meet. O(n log n + the pairs that meet on x); a pile of 16,000 circles takes a few
// milliseconds. The unit suite checks it against an all-pairs loop.
inline std::vector<IndexPair> sweep_pairs(const std::vector<Aabb>& boxes) {
  std::vector<std::uint32_t> order(boxes.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::uint32_t i, std::uint32_t j) {
    return boxes[i].min.x < boxes[j].min.x || (boxes[i].min.x == boxes[j].min.x && i < j);
  });
  std::vector<IndexPair> pairs;
  for (std::size_t p = 0; p < order.size(); ++p) {
    const Aabb& a = boxes[order[p]];
    for (std::size_t q = p + 1; q < order.size(); ++q) {
      const Aabb& b = boxes[order[q]];
      if (b.min.x > a.max.x) break;  // and so is every box after it
      if (a.min.y <= b.max.y && b.min.y <= a.max.y) {
        pairs.push_back({std::min(order[p], order[q]), std::max(order[p], order[q])});
      }
    }
  }
  return pairs;
}

// The deepest overlap between any two bodies of which at least one is dynamic
// (static geometry may touch itself: tiled floors do). Candidates come from
// sweep_pairs, not from the core's grid.
inline double max_overlap(const std::vector<BodyState>& bodies) {
  std::vector<Aabb> boxes;
  boxes.reserve(bodies.size());
  for (const BodyState& body : bodies) boxes.push_back(aabb_of(body));
  double deepest = 0.0;
  for (const IndexPair& pair : sweep_pairs(boxes)) {
    const BodyState& a = bodies[pair.a];
    const BodyState& b = bodies[pair.b];
    if (a.motion == Motion::Static && b.motion == Motion::Static) continue;
    deepest = std::max(deepest, overlap_depth(a, b));
  }
  return deepest;
}

inline double kinetic_energy(const std::vector<BodyState>& bodies) {
  double energy = 0.0;
  for (const BodyState& body : bodies) {
    if (body.motion == Motion::Dynamic)
      energy += 0.5 * body.mass * dot(body.velocity, body.velocity);
  }
  return energy;
}

inline bool all_finite(const std::vector<BodyState>& bodies) {
  return std::all_of(bodies.begin(), bodies.end(), [](const BodyState& body) {
    return is_finite(body.position) && is_finite(body.velocity) && is_finite(body.acceleration);
  });
}

// A fixture owning one world. Tests that need other settings call reset() first.
class WorldTest : public ::testing::Test {
 protected:
  void reset(const WorldSettings& settings) { world_ = World(settings); }

  BodyId add(const BodyDef& def) { return add_or_fail(world_, def); }
  BodyId make_box(Vec2 center, Vec2 half_extents = {0.5, 0.5}, double mass = 1.0) {
    BodyDef def = box_def(center, half_extents);
    def.mass = mass;
    return add(def);
  }
  BodyId make_static_box(Vec2 center, Vec2 half_extents) {
    return add(box_def(center, half_extents, Motion::Static));
  }
  BodyId make_circle(Vec2 center, double radius = 0.5, double mass = 1.0) {
    BodyDef def = circle_def(center, radius);
    def.mass = mass;
    return add(def);
  }
  BodyId make_static_circle(Vec2 center, double radius) {
    return add(circle_def(center, radius, Motion::Static));
  }
  // A static floor whose top surface is the line y = top.
  BodyId make_floor(double top, double half_width = 50.0) {
    return make_static_box({0.0, top - 0.5}, {half_width, 0.5});
  }

  void step_n(int n, double dt = kDt) {
    for (int i = 0; i < n; ++i) world_.step(dt);
  }

  BodyState state(BodyId id) const {
    const auto body = world_.body(id);
    EXPECT_TRUE(body.has_value()) << "no body with id " << id.index << "/" << id.generation;
    return body.value_or(BodyState{});
  }
  Vec2 position(BodyId id) const { return state(id).position; }
  Vec2 velocity(BodyId id) const { return state(id).velocity; }

  World world_{};
};

}  // namespace phys::testing

namespace phys::testing {

// The highest point of a simulated free-flight trajectory. With the Exact
// integrator a body in free flight follows the parabola exactly inside each step,
// so when v_y turns from positive to non-positive during a step the top of that
// step's parabola, y + v_y^2 / (2|g|) from the step's start, is part of the
// simulated trajectory; sampling only the step ends would under-read an apex by up
// to |g| dt^2 / 8 (0.34 mm at 60 Hz).
class ApexTracker {
 public:
  explicit ApexTracker(double gravity_magnitude) : g_(gravity_magnitude) {}

  // Feed the state at the end of every step. Returns true when an apex was just
  // passed (the value is then in last_apex()).
  bool add(double y, double vy) {
    bool passed = false;
    if (have_previous_ && previous_vy_ > 0.0 && vy <= 0.0) {
      last_apex_ =
          std::max({previous_y_ + previous_vy_ * previous_vy_ / (2.0 * g_), previous_y_, y});
      passed = true;
    }
    previous_y_ = y;
    previous_vy_ = vy;
    have_previous_ = true;
    return passed;
  }
  double last_apex() const { return last_apex_; }

 private:
  double g_;
  bool have_previous_ = false;
  double previous_y_ = 0.0;
  double previous_vy_ = 0.0;
  double last_apex_ = 0.0;
};

}  // namespace phys::testing
