#include "observers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <optional>
#include <utility>
#include <vector>

#include "closed_form.h"
#include "overlap.h"
#include "scenes/scenes.h"

namespace bench {
namespace {

const BodySpec& first_dynamic(const SceneSpec& scene) {
  for (const BodySpec& body : scene.bodies) {
    if (!body.is_static) return body;
  }
  return scene.bodies.front();
}

std::string format_notes(std::initializer_list<std::pair<const char*, double>> entries) {
  std::string notes;
  for (const auto& [key, value] : entries) {
    if (!notes.empty()) notes += ';';
    char text[64];
    std::snprintf(text, sizeof text, "%s=%.6g", key, value);
    notes += text;
  }
  return notes;
}

// Largest distance from the closed form of dv/dt = a + g - k v, over every step.
class TrajectoryObserver final : public Observer {
 public:
  explicit TrajectoryObserver(const SceneSpec& scene)
      : scene_(scene), body_(first_dynamic(scene)) {}

  void observe(int step, std::span<const BodySample> dynamic) override {
    const double t = step * scene_.dt;
    const phys::Vec2 a = body_.acceleration + scene_.gravity;
    const AxisState x =
        closed_form_axis(body_.position.x, body_.velocity.x, a.x, body_.friction.x, t);
    const AxisState y =
        closed_form_axis(body_.position.y, body_.velocity.y, a.y, body_.friction.y, t);
    const phys::Vec2 p = dynamic[0].position;
    const phys::Vec2 v = dynamic[0].velocity;
    max_error_ = std::max(max_error_, phys::length(p - phys::Vec2{x.position, y.position}));
    max_velocity_error_ =
        std::max(max_velocity_error_, phys::length(v - phys::Vec2{x.velocity, y.velocity}));
  }

  Measures finish() override {
    Measures m;
    m.error_name = "traj_err_m";
    m.error = max_error_;
    m.notes = format_notes({{"vel_err_mps", max_velocity_error_}});
    return m;
  }

 private:
  const SceneSpec& scene_;
  const BodySpec& body_;
  double max_error_ = 0.0;
  double max_velocity_error_ = 0.0;
};

// Velocity against v0*exp(-k t); never changing sign, never growing.
class FrictionObserver final : public Observer {
 public:
  explicit FrictionObserver(const SceneSpec& scene)
      : scene_(scene),
        v0_(first_dynamic(scene).velocity.x),
        k_(first_dynamic(scene).friction.x),
        previous_(v0_) {}

  void observe(int step, std::span<const BodySample> dynamic) override {
    const double v = dynamic[0].velocity.x;
    const double exact = v0_ * std::exp(-k_ * step * scene_.dt);
    max_error_ = std::max(max_error_, std::abs(v - exact) / std::abs(v0_));
    if (v * v0_ < 0.0) sign_changes_ += 1.0;
    if (std::abs(v) > std::abs(previous_)) growths_ += 1.0;
    previous_ = v;
  }

  Measures finish() override {
    Measures m;
    m.error_name = "decay_err_rel";
    m.error = max_error_;
    m.notes = format_notes(
        {{"dt_k", k_ * scene_.dt}, {"sign_changes", sign_changes_}, {"growths", growths_}});
    return m;
  }

 private:
  const SceneSpec& scene_;
  double v0_;
  double k_;
  double previous_;
  double max_error_ = 0.0;
  double sign_changes_ = 0.0;
  double growths_ = 0.0;
};

// Apex heights of the ball's bottom above the floor, each from the last state
// before the top of a flight: y + vy^2/(2g) (the sampled maximum alone would be off
// by up to g dt^2/8 = 0.34 mm, 3.5% of the fifth apex at e = 0.5).
class BounceObserver final : public Observer {
 public:
  explicit BounceObserver(const SceneSpec& scene)
      : scene_(scene), e_(first_dynamic(scene).restitution), radius_(first_dynamic(scene).radius) {}

  void observe(int step, std::span<const BodySample> dynamic) override {
    const BodySample& ball = dynamic[0];
    const double g = -scene_.gravity.y;
    if (previous_vy_ > 0.0 && ball.velocity.y <= 0.0) {
      apexes_.push_back(apex_through(previous_y_ - radius_, previous_vy_, g));
    }
    const bool at_rest = ball.velocity.x == 0.0 && ball.velocity.y == 0.0;
    if (!at_rest) rest_step_ = -1;
    if (at_rest && rest_step_ < 0) rest_step_ = step;
    previous_y_ = ball.position.y;
    previous_vy_ = ball.velocity.y;
  }

  Measures finish() override {
    Measures m;
    const double h0 = scenes::kBounceHeight;
    if (e_ >= 1.0) {
      constexpr std::size_t kBounces = 36;
      m.error_name = "apex36_err_rel";
      if (apexes_.size() >= kBounces) m.error = std::abs(apexes_[kBounces - 1] - h0) / h0;
      double worst = 0.0;
      for (double apex : apexes_) worst = std::max(worst, std::abs(apex - h0) / h0);
      m.energy_drift = worst;
      m.notes = format_notes(
          {{"apexes", static_cast<double>(apexes_.size())},
           {"apex36_m", apexes_.size() >= kBounces ? apexes_[kBounces - 1] : Measures::kNone}});
    } else {
      constexpr std::size_t kBounces = 5;
      m.error_name = "apex5_err_rel";
      if (apexes_.size() >= kBounces) {
        double worst = 0.0;
        for (std::size_t n = 1; n <= kBounces; ++n) {
          const double expected = std::pow(e_, 2.0 * static_cast<double>(n)) * h0;
          worst = std::max(worst, std::abs(apexes_[n - 1] - expected) / expected);
        }
        m.error = worst;
      }
      m.notes = format_notes(
          {{"apexes", static_cast<double>(apexes_.size())},
           {"rest_time_s", rest_step_ < 0 ? Measures::kNone : rest_step_ * scene_.dt}});
    }
    return m;
  }

 private:
  const SceneSpec& scene_;
  double e_;
  double radius_;
  double previous_y_ = 0.0;
  double previous_vy_ = 0.0;
  std::vector<double> apexes_;
  int rest_step_ = -1;
};

// Columns and pyramids: the top box's drift from its start (and from t = 1 s, once
// the first contacts have settled), and the deepest overlap over the samples.
class StackObserver final : public Observer {
 public:
  explicit StackObserver(const SceneSpec& scene) : scene_(scene) {
    std::size_t index = 0;
    double top = -1e300;
    for (const BodySpec& body : scene.bodies) {
      if (body.is_static) continue;
      if (body.position.y > top) {
        top = body.position.y;
        top_index_ = index;
        start_ = body.position;
      }
      ++index;
    }
  }

  void observe(int step, std::span<const BodySample> dynamic) override {
    const phys::Vec2 top = dynamic[top_index_].position;
    if (!reference_ && step * scene_.dt >= 1.0) reference_ = top;
    drift_ = std::max(drift_, phys::length(top - start_));
    if (reference_) rest_drift_ = std::max(rest_drift_, phys::length(top - *reference_));
    overlap_ = std::max(overlap_, max_overlap(scene_, dynamic, 1e300).max_depth);
    escaped_ = static_cast<long>(non_finite_count(dynamic));
  }

  Measures finish() override {
    Measures m;
    m.error_name = "top_drift_m";
    m.error = drift_;
    m.top_drift = drift_;
    m.max_overlap = overlap_;
    m.non_finite = escaped_;
    m.notes = format_notes({{"drift_after_1s_m", rest_drift_}});
    return m;
  }

 private:
  const SceneSpec& scene_;
  std::size_t top_index_ = 0;
  phys::Vec2 start_{};
  std::optional<phys::Vec2> reference_;
  double drift_ = 0.0;
  double rest_drift_ = 0.0;
  double overlap_ = 0.0;
  long escaped_ = 0;
};

// Rain and piles: nothing escapes or turns NaN; the overlap once settled; kinetic
// energy over the last window must not grow.
class PileObserver final : public Observer {
 public:
  explicit PileObserver(const SceneSpec& scene) : scene_(scene) {
    for (const BodySpec& body : scene.bodies) {
      if (!body.is_static) masses_.push_back(body.mass);
    }
  }

  void observe(int step, std::span<const BodySample> dynamic) override {
    escaped_ = std::max(escaped_, static_cast<long>(escaped_count(scene_, dynamic)));
    non_finite_ = std::max(non_finite_, static_cast<long>(non_finite_count(dynamic)));
    const double energy = kinetic_energy(dynamic);
    const bool in_last_window = scene_.last_window > 0 && step > scene_.steps - scene_.last_window;
    if (in_last_window) {
      if (!settled_energy_) settled_energy_ = energy;
      max_settled_energy_ = std::max(max_settled_energy_, energy);
    }
    if (step == scene_.steps) {
      final_energy_ = energy;
      const OverlapResult overlap = max_overlap(scene_, dynamic, 0.01);
      overlap_ = overlap.max_depth;
      deep_pairs_ = static_cast<double>(overlap.overlapping_pairs);
    }
  }

  Measures finish() override {
    Measures m;
    m.error_name = "max_overlap_m";
    m.error = overlap_;
    m.max_overlap = overlap_;
    m.escaped = escaped_;
    m.non_finite = non_finite_;
    if (settled_energy_) m.energy_drift = max_settled_energy_ - *settled_energy_;
    m.notes = format_notes({{"pairs_over_1cm", deep_pairs_}, {"final_ke_j", final_energy_}});
    return m;
  }

 private:
  double kinetic_energy(std::span<const BodySample> dynamic) const {
    double energy = 0.0;
    for (std::size_t i = 0; i < dynamic.size(); ++i) {
      energy += 0.5 * masses_[i] * phys::dot(dynamic[i].velocity, dynamic[i].velocity);
    }
    return energy;
  }

  const SceneSpec& scene_;
  std::vector<double> masses_;
  long escaped_ = 0;
  long non_finite_ = 0;
  std::optional<double> settled_energy_;
  double max_settled_energy_ = 0.0;
  double final_energy_ = 0.0;
  double overlap_ = 0.0;
  double deep_pairs_ = 0.0;
};

// The stage-cost scenes measure time only; the runner adds the stage counters.
class StagesObserver final : public Observer {
 public:
  explicit StagesObserver(const SceneSpec& scene) : scene_(scene) {}
  void observe(int, std::span<const BodySample> dynamic) override {
    non_finite_ = std::max(non_finite_, static_cast<long>(non_finite_count(dynamic)));
    escaped_ = std::max(escaped_, static_cast<long>(escaped_count(scene_, dynamic)));
  }
  Measures finish() override {
    Measures m;
    m.escaped = escaped_;
    m.non_finite = non_finite_;
    return m;
  }

 private:
  const SceneSpec& scene_;
  long non_finite_ = 0;
  long escaped_ = 0;
};

}  // namespace

std::unique_ptr<Observer> make_observer(ObserverKind kind, const SceneSpec& scene) {
  switch (kind) {
    case ObserverKind::Trajectory:
      return std::make_unique<TrajectoryObserver>(scene);
    case ObserverKind::FrictionDecay:
      return std::make_unique<FrictionObserver>(scene);
    case ObserverKind::Bounce:
      return std::make_unique<BounceObserver>(scene);
    case ObserverKind::Stack:
      return std::make_unique<StackObserver>(scene);
    case ObserverKind::Pile:
      return std::make_unique<PileObserver>(scene);
    case ObserverKind::Stages:
      return std::make_unique<StagesObserver>(scene);
  }
  return nullptr;
}

}  // namespace bench
