#include "runner.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <span>

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
  sum.integrate += step.integrate;
  sum.broadphase += step.broadphase;
  sum.narrowphase += step.narrowphase;
  sum.resolve += step.resolve;
  sum.sleep += step.sleep;
  sum.total += step.total;
}

void scale_profile(phys::StepProfile& sum, double factor) {
  sum.integrate *= factor;
  sum.broadphase *= factor;
  sum.narrowphase *= factor;
  sum.resolve *= factor;
  sum.sleep *= factor;
  sum.total *= factor;
}

// What each stage did during the run: shows a skipped stage as 0.
std::string counter_notes(const phys::StageCounters& c) {
  char text[320];
  std::snprintf(text, sizeof text,
                "gravity_passes=%llu;friction_passes=%llu;restitution_passes=%llu;"
                "box_box_tests=%llu;circle_circle_tests=%llu;circle_box_tests=%llu;"
                "sleeping_skipped=%llu;swept_hits=%llu",
                static_cast<unsigned long long>(c.gravity_passes),
                static_cast<unsigned long long>(c.friction_passes),
                static_cast<unsigned long long>(c.restitution_passes),
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

RunRow run_once(const SceneEntry& entry, const SceneSpec& scene, EngineKind engine_kind,
                const OursSetting& setting, bool sleeping, int timeline_steps) {
  EngineOptions options;
  options.ours.integrator = setting.integrator;
  options.ours.substeps = setting.substeps;
  options.ours.position_iterations = setting.iterations;
  options.ours.velocity_iterations = setting.velocity_iterations;
  options.ours.profile = true;
  options.sleeping = sleeping;
  auto engine = make_engine(engine_kind, scene, options);

  RunRow row;
  row.scene = scene.name;
  row.engine = engine_kind;
  row.sleeping = sleeping;
  row.bodies = scene.bodies.size();
  row.steps = scene.steps;
  row.iterations = engine->iterations_label();
  if (engine_kind == EngineKind::Ours) {
    row.integrator = phys::to_string(setting.integrator);
    row.substeps = setting.substeps;
    row.default_setting = is_default(setting);
  } else {
    row.integrator = "peer";
  }

  auto observer = make_observer(entry.observer, scene);
  std::vector<double> seconds;
  std::vector<double> cpu_seconds;
  seconds.reserve(static_cast<std::size_t>(scene.steps));
  cpu_seconds.reserve(static_cast<std::size_t>(scene.steps));
  std::vector<BodySample> samples;
  std::vector<std::size_t> awake_after_window;
  const phys::StepProfile* profile = engine->last_profile();
  for (int step = 1; step <= scene.steps; ++step) {
    const double cpu_start = thread_cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    engine->step(scene.dt);
    const auto stop = std::chrono::steady_clock::now();
    cpu_seconds.push_back(thread_cpu_seconds() - cpu_start);
    seconds.push_back(std::chrono::duration<double>(stop - start).count());
    if (profile != nullptr) add_profile(row.profile_mean, *profile);
    if (step % timeline_steps == 0 || step == scene.steps) {
      awake_after_window.push_back(engine->awake_count());
    }
    if (step % scene.sample_every == 0 || step == scene.steps) {
      engine->sample(samples);
      observer->observe(step, samples);
    }
  }

  const std::span<const double> all(seconds);
  row.ms_median = median_ms(all);
  row.ms_mean = mean_ms(all);
  const std::span<const double> cpu(cpu_seconds);
  row.cpu_ms_mean = mean_ms(cpu);
  if (scene.first_window > 0 && scene.first_window <= scene.steps) {
    const auto window = static_cast<std::size_t>(scene.first_window);
    row.ms_first = median_ms(all.first(window));
    row.cpu_ms_first = mean_ms(cpu.first(window));
  }
  if (scene.last_window > 0 && scene.last_window <= scene.steps) {
    const auto window = static_cast<std::size_t>(scene.last_window);
    row.ms_last = median_ms(all.last(window));
    row.cpu_ms_last = mean_ms(cpu.last(window));
  }
  row.awake_end = engine->awake_count();
  row.timeline = timeline_windows(all, cpu, awake_after_window, timeline_steps, scene.dt);
  row.measures = observer->finish();
  if (profile != nullptr) {
    row.has_profile = true;
    scale_profile(row.profile_mean, 1.0 / scene.steps);
  }
  if (const phys::StageCounters* counters = engine->counters()) {
    if (!row.measures.notes.empty()) row.measures.notes += ';';
    row.measures.notes += counter_notes(*counters);
  }
  return row;
}

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
                          defaults.velocity_iterations});
    } else {
      for (phys::Integrator integrator : config.integrators) {
        for (int substeps : config.substeps) {
          for (int iterations : config.iterations) {
            for (int velocity_iterations : config.velocity_iterations)
              settings.push_back({integrator, substeps, iterations, velocity_iterations});
          }
        }
      }
    }
    for (bool sleeping : sleep_modes) {
      for (EngineKind engine : config.engines) {
        if (!engine_available(engine)) continue;
        if (engine == EngineKind::Ours) {
          for (const OursSetting& setting : settings)
            emit(run_once(entry, scene, engine, setting, sleeping, config.timeline_steps));
        } else if (entry.peers_by_default || config.peers_on_all_scenes) {
          emit(run_once(entry, scene, engine, OursSetting{}, sleeping, config.timeline_steps));
        }
      }
    }
  }
}

}  // namespace bench
