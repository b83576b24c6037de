#include "runner.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <span>
#include <utility>

#include "timing.h"

namespace bench {
namespace {

bool is_default(const OursSetting& setting) {
  const phys::WorldSettings defaults{};
  return setting.integrator == defaults.integrator && setting.substeps == defaults.substeps &&
         setting.iterations == defaults.position_iterations &&
         setting.velocity_iterations == defaults.velocity_iterations;
}

void add_profile(phys::StepProfile& sum, const phys::StepProfile& step) {
  sum.order_and_integrate += step.order_and_integrate;
  sum.candidates += step.candidates;
  sum.moves += step.moves;
  sum.position_passes += step.position_passes;
  sum.contact_events += step.contact_events;
  sum.velocity_solver += step.velocity_solver;
  sum.bounds_and_sleep += step.bounds_and_sleep;
  sum.total += step.total;
}

void scale_profile(phys::StepProfile& sum, double factor) {
  sum.order_and_integrate *= factor;
  sum.candidates *= factor;
  sum.moves *= factor;
  sum.position_passes *= factor;
  sum.contact_events *= factor;
  sum.velocity_solver *= factor;
  sum.bounds_and_sleep *= factor;
  sum.total *= factor;
}

// What each stage did during the run: shows a skipped stage as 0.
std::string counter_notes(const phys::StageCounters& c) {
  char text[320];
  std::snprintf(text, sizeof text,
                "gravity_passes=%llu;friction_passes=%llu;velocity_solves=%llu;"
                "box_box_tests=%llu;circle_circle_tests=%llu;circle_box_tests=%llu;"
                "sleeping_skipped=%llu;swept_hits=%llu",
                static_cast<unsigned long long>(c.gravity_passes),
                static_cast<unsigned long long>(c.friction_passes),
                static_cast<unsigned long long>(c.velocity_solves),
                static_cast<unsigned long long>(c.box_box_tests),
                static_cast<unsigned long long>(c.circle_circle_tests),
                static_cast<unsigned long long>(c.circle_box_tests),
                static_cast<unsigned long long>(c.sleeping_bodies_skipped),
                static_cast<unsigned long long>(c.swept_hits));
  return text;
}

// CPU seconds this thread has used: unlike wall time, it does not count the time
// other processes on a shared machine hold the core.
double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
}

}  // namespace

RunInProgress::RunInProgress(const SceneEntry& entry, const SceneSpec& scene,
                             EngineKind engine_kind, const OursSetting& setting, bool sleeping,
                             int timeline_steps)
    : scene_(scene), timeline_steps_(timeline_steps) {
  EngineOptions options;
  options.ours.integrator = setting.integrator;
  options.ours.substeps = setting.substeps;
  options.ours.position_iterations = setting.iterations;
  options.ours.velocity_iterations = setting.velocity_iterations;
  options.ours.relaxed_position_passes = setting.relaxed_position_passes;
  options.ours.profile = true;
  options.sleeping = sleeping;
  engine_ = make_engine(engine_kind, scene, options);

  row_.scene = scene.name;
  row_.engine = engine_kind;
  row_.sleeping = sleeping;
  row_.bodies = scene.bodies.size();
  row_.steps = scene.steps;
  row_.iterations = engine_->iterations_label();
  if (runs_our_settings(engine_kind)) {
    row_.integrator = phys::to_string(setting.integrator);
    row_.substeps = setting.substeps;
    row_.default_setting = is_default(setting);
  } else {
    row_.integrator = "peer";
  }
  observer_ = make_observer(entry.observer, scene);
  seconds_.reserve(static_cast<std::size_t>(scene.steps));
  cpu_seconds_.reserve(static_cast<std::size_t>(scene.steps));
}

void RunInProgress::advance(int steps) {
  const phys::StepProfile* profile = engine_->last_profile();
  for (int n = 0; n < steps && !done(); ++n) {
    const int step = ++steps_done_;
    const double cpu_start = thread_cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    engine_->step(scene_.dt);
    const auto stop = std::chrono::steady_clock::now();
    cpu_seconds_.push_back(thread_cpu_seconds() - cpu_start);
    seconds_.push_back(std::chrono::duration<double>(stop - start).count());
    if (profile != nullptr) add_profile(row_.profile_mean, *profile);
    if (step % timeline_steps_ == 0 || step == scene_.steps) {
      awake_after_window_.push_back(engine_->awake_count());
    }
    if (step % scene_.sample_every == 0 || step == scene_.steps) {
      engine_->sample(samples_);
      observer_->observe(step, samples_);
    }
  }
}

RunRow RunInProgress::finish() {
  RunRow row = std::move(row_);
  const std::span<const double> all(seconds_);
  row.ms_median = median_ms(all);
  row.ms_mean = mean_ms(all);
  const std::span<const double> cpu(cpu_seconds_);
  row.cpu_ms_mean = mean_ms(cpu);
  if (scene_.first_window > 0 && scene_.first_window <= scene_.steps) {
    const auto window = static_cast<std::size_t>(scene_.first_window);
    row.ms_first = median_ms(all.first(window));
    row.cpu_ms_first = mean_ms(cpu.first(window));
  }
  if (scene_.last_window > 0 && scene_.last_window <= scene_.steps) {
    const auto window = static_cast<std::size_t>(scene_.last_window);
    row.ms_last = median_ms(all.last(window));
    row.cpu_ms_last = mean_ms(cpu.last(window));
  }
  row.awake_end = engine_->awake_count();
  row.timeline = timeline_windows(all, cpu, awake_after_window_, timeline_steps_, scene_.dt);
  row.measures = observer_->finish();
  if (engine_->last_profile() != nullptr) {
    row.has_profile = true;
    scale_profile(row.profile_mean, 1.0 / scene_.steps);
  }
  if (const phys::StageCounters* counters = engine_->counters()) {
    if (!row.measures.notes.empty()) row.measures.notes += ';';
    row.measures.notes += counter_notes(*counters);
  }
  if (const auto hash = engine_->state_hash()) {
    char text[40];
    std::snprintf(text, sizeof text, "state_hash=%016llx", static_cast<unsigned long long>(*hash));
    if (!row.measures.notes.empty()) row.measures.notes += ';';
    row.measures.notes += text;
  }
  return row;
}

RunRow run_once(const SceneEntry& entry, const SceneSpec& scene, EngineKind engine_kind,
                const OursSetting& setting, bool sleeping, int timeline_steps) {
  RunInProgress run(entry, scene, engine_kind, setting, sleeping, timeline_steps);
  run.advance(scene.steps);
  return run.finish();
}

namespace {
// All the runs at once, taking turns of config.interleave_steps steps: a machine
// whose speed drifts over minutes then slows every engine alike, where one run
// after another gave each engine a different part of the drift. Each engine's
// steps are the same as in a run of its own; only the times change.
void run_interleaved(const SceneEntry& entry, const SceneSpec& scene,
                     const std::vector<std::pair<EngineKind, OursSetting>>& runs, bool sleeping,
                     const GridConfig& config, const std::function<void(const RunRow&)>& emit) {
  std::vector<RunInProgress> in_progress;
  in_progress.reserve(runs.size());
  for (const auto& [engine, setting] : runs) {
    in_progress.emplace_back(entry, scene, engine, setting, sleeping, config.timeline_steps);
  }
  for (bool any_left = true; any_left;) {
    any_left = false;
    for (RunInProgress& run : in_progress) {
      run.advance(config.interleave_steps);
      any_left = any_left || !run.done();
    }
  }
  for (RunInProgress& run : in_progress) emit(run.finish());
}
}  // namespace

void run_grid(const std::vector<SceneEntry>& scenes, const Mode& mode, const GridConfig& config,
              const std::function<void(const RunRow&)>& emit) {
  const phys::WorldSettings defaults{};
  for (const SceneEntry& entry : scenes) {
    const SceneSpec scene = entry.build(mode);
    std::vector<bool> sleep_modes = config.sleep_modes;
    if (sleep_modes.empty()) {
      sleep_modes = entry.sleep_matters ? std::vector<bool>{true, false} : std::vector<bool>{true};
    }
    std::vector<OursSetting> settings;
    if (entry.large && !config.full_grid_on_large) {
      settings.push_back({defaults.integrator, defaults.substeps, defaults.position_iterations,
                          defaults.velocity_iterations, config.relaxed_position_passes});
    } else {
      for (phys::Integrator integrator : config.integrators) {
        for (int substeps : config.substeps) {
          for (int iterations : config.iterations) {
            for (int velocity_iterations : config.velocity_iterations)
              settings.push_back({integrator, substeps, iterations, velocity_iterations,
                                  config.relaxed_position_passes});
          }
        }
      }
    }
    for (bool sleeping : sleep_modes) {
      // The runs of this scene and sleep mode, in the order their rows come out.
      std::vector<std::pair<EngineKind, OursSetting>> runs;
      for (EngineKind engine : config.engines) {
        if (!engine_available(engine)) continue;
        if (runs_our_settings(engine)) {
          for (const OursSetting& setting : settings) runs.push_back({engine, setting});
        } else if (entry.peers_by_default || config.peers_on_all_scenes) {
          runs.push_back({engine, OursSetting{}});
        }
      }
      if (config.interleave_steps > 0) {
        run_interleaved(entry, scene, runs, sleeping, config, emit);
        continue;
      }
      for (const auto& [engine, setting] : runs) {
        emit(run_once(entry, scene, engine, setting, sleeping, config.timeline_steps));
      }
    }
  }
}

}  // namespace bench
