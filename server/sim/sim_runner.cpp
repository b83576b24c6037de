#include "sim_runner.h"

#include <chrono>

namespace sim {

RunSummary run_scene(const scene::SceneDef& scene, const RunOptions& options,
                     const std::function<void(const Progress&)>& on_progress) {
  phys::World world = scene::build_world(scene);
  using Clock = std::chrono::steady_clock;
  Clock::duration stepping{};
  for (std::uint64_t step = 1; step <= options.steps; ++step) {
    const Clock::time_point start = Clock::now();
    world.step(options.dt);
    stepping += Clock::now() - start;
    if (on_progress && options.progress_every > 0 && step % options.progress_every == 0) {
      on_progress({step, world.state_hash(), world.awake_body_count(),
                   std::chrono::duration<double>(stepping).count()});
    }
  }
  RunSummary summary;
  summary.steps = options.steps;
  summary.bodies = world.body_count();
  summary.dynamic_bodies = world.dynamic_body_count();
  summary.awake_bodies = world.awake_body_count();
  summary.dt = options.dt;
  summary.total_seconds = std::chrono::duration<double>(stepping).count();
  summary.state_hash = world.state_hash();
  return summary;
}

}  // namespace sim
