// physics-contact-bench: what contact events cost the step. Runs a named scene with
// World::set_contact_events off and on, interleaved, and prints one CSV row per
// setting: the step's CPU time (the best of the repeats), the events and the work the
// stage counters show. The state hash must be the same both ways (exit 1 if not).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <limits>
#include <string>
#include <utility>

#include "parse_flags.h"
#include "physics/world.h"
#include "scenes/scenes.h"

namespace {

phys::World build(const scenes::SceneSpec& scene, bool events) {
  phys::WorldSettings settings;
  settings.gravity = scene.gravity;
  phys::World world(settings);
  scenes::add_to_world(world, scene);
  world.set_contact_events(events);
  return world;
}

// This thread's CPU time: other processes on a shared machine disturb it much less
// than wall time.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Run {
  double seconds = std::numeric_limits<double>::infinity();  // best of the repeats
  std::uint64_t hash = 0;
  std::uint64_t events = 0;
  phys::StageCounters counters;
};

void run_once(const scenes::SceneSpec& scene, bool events, Run& best) {
  phys::World world = build(scene, events);
  std::uint64_t produced = 0;
  const double start = cpu_seconds();
  for (int i = 0; i < scene.steps; ++i) {
    world.step(scene.dt);
    produced += world.contact_events().size();
  }
  const double seconds = cpu_seconds() - start;
  best.seconds = std::min(best.seconds, seconds);
  best.hash = world.state_hash();
  best.events = produced;
  best.counters = world.counters();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"physics-contact-bench: the step's cost with contact events off and on"};
  std::string scene_name = "rain";
  int count = 4000;
  int steps = 600;
  int repeats = 3;
  app.add_option("--scene", scene_name, "rain (circles onto a floor) or pile (circles and boxes)")
      ->check(CLI::IsMember({"rain", "pile"}))
      ->capture_default_str();
  app.add_option("--count", count, "Bodies")->check(CLI::Range(1, 100000))->capture_default_str();
  app.add_option("--steps", steps, "Steps at 60 Hz")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--repeats", repeats, "Runs per setting, interleaved; the best is kept")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  if (const auto exit_code = bench::parse_flags(app, argc, argv)) return *exit_code;

  scenes::SceneSpec scene =
      scene_name == "rain" ? scenes::rain_scene(count, steps, 0, 0) : scenes::pile_scene(count);
  scene.steps = steps;
  Run off;
  Run on;
  for (int r = 0; r < repeats; ++r) {
    run_once(scene, false, off);
    run_once(scene, true, on);
  }
  std::printf(
      "scene,bodies,steps,contact_events,cpu_ms_per_step,events,contact_pair_tests,"
      "circle_circle_tests,circle_box_tests,box_box_tests,contacts,state_hash\n");
  const std::pair<const char*, const Run*> rows[] = {{"off", &off}, {"on", &on}};
  for (const auto& [label, run] : rows) {
    const phys::StageCounters& c = run->counters;
    std::printf(
        "%s,%d,%d,%s,%.4f,%llu,%llu,%llu,%llu,%llu,%llu,%016llx\n", scene_name.c_str(), count,
        steps, label, 1e3 * run->seconds / steps, static_cast<unsigned long long>(run->events),
        static_cast<unsigned long long>(c.contact_pair_tests),
        static_cast<unsigned long long>(c.circle_circle_tests),
        static_cast<unsigned long long>(c.circle_box_tests),
        static_cast<unsigned long long>(c.box_box_tests),
        static_cast<unsigned long long>(c.contacts), static_cast<unsigned long long>(run->hash));
  }
  std::fflush(stdout);
  std::fprintf(stderr, "contact events on: %+.1f%% CPU time a step\n",
               100.0 * (on.seconds / off.seconds - 1.0));
  if (on.hash != off.hash) {
    std::fprintf(stderr, "physics-contact-bench: state hash differs with events on\n");
    return 1;
  }
  return 0;
}
