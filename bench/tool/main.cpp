// physics-bench: named scenes over a grid of settings, on ours and on the peers
// that this build links, printed as CSV (stdout or --csv), with a human summary and
// the per-phase profile on stderr. See docs/ACCURACY.md.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "catalog.h"
#include "finite_range.h"
#include "parse_flags.h"
#include "peer_banners.h"
#include "report.h"
#include "runner.h"

namespace {

std::optional<phys::Integrator> integrator_from_string(const std::string& name) {
  for (phys::Integrator integrator :
       {phys::Integrator::ExplicitEuler, phys::Integrator::SemiImplicitEuler,
        phys::Integrator::Exact}) {
    if (name == phys::to_string(integrator)) return integrator;
  }
  return std::nullopt;
}

bool selected(const std::string& name, const std::vector<std::string>& patterns) {
  return std::any_of(patterns.begin(), patterns.end(), [&](const std::string& pattern) {
    if (pattern == "all") return true;
    // "rain" picks rain-16000; "stages" every stages-* scene.
    return name == pattern || name.rfind(pattern + "-", 0) == 0;
  });
}

// Opens an output the user named; says so on stderr when it cannot.
bool open_output(std::ofstream& file, const std::string& path) {
  file.open(path);
  if (!file) std::cerr << "physics-bench: cannot write " << path << '\n';
  return static_cast<bool>(file);
}

// The peers run on the scenes that name them (rain and pyramid) unless
// --peers-everywhere: asked for, they would otherwise be left out without a word.
void say_where_peers_do_not_run(const std::vector<bench::SceneEntry>& scenes,
                                const bench::GridConfig& grid) {
  if (grid.peers_on_all_scenes) return;
  std::string peers;
  for (const bench::EngineKind engine : grid.engines) {
    if (bench::runs_our_settings(engine)) continue;
    peers += (peers.empty() ? "" : ", ") + std::string(bench::to_string(engine));
  }
  std::string alone;
  for (const bench::SceneEntry& entry : scenes) {
    if (!entry.peers_by_default) alone += (alone.empty() ? "" : ", ") + entry.name;
  }
  if (peers.empty() || alone.empty()) return;
  std::cerr << "physics-bench: " << peers << " run on their own scenes only (add "
            << "--peers-everywhere to run them on every scene); ours alone on: " << alone << '\n';
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"physics-bench: speed against error, ours and the peers in one run"};
  std::vector<std::string> scene_names{"all"};
  std::vector<std::string> engine_names{"ours", "box2d", "chipmunk"};
  std::vector<std::string> integrator_names{phys::to_string(phys::Integrator::ExplicitEuler),
                                            phys::to_string(phys::Integrator::SemiImplicitEuler),
                                            phys::to_string(phys::Integrator::Exact)};
  std::vector<int> substeps{1, 2, 4, 8};
  std::vector<int> iterations{1, 2, 4, 8};
  std::vector<int> velocity_iterations{phys::WorldSettings{}.velocity_iterations};
  std::string sleep = "auto";
  std::string csv_path;
  std::string ratios_path;
  std::string timeline_path;
  bench::Mode mode;
  bench::GridConfig grid;
  bool list = false;

  app.add_option("--scenes", scene_names,
                 "Scenes, or prefixes of them (rain, stages, friction-dtk), or all")
      ->delimiter(',');
  app.add_option("--engines", engine_names,
                 "Engines: ours, box2d, chipmunk, and baseline (another revision's core, in a "
                 "build configured with -DPHYSICS_BASELINE_CORE=DIR)")
      ->delimiter(',');
  app.add_option("--integrators", integrator_names,
                 "Our integrators: explicit-euler, semi-implicit-euler, exact")
      ->delimiter(',');
  app.add_option("--substeps", substeps, "Our substep counts")
      ->delimiter(',')
      ->check(CLI::Range(1, 64));
  app.add_option("--iterations", iterations, "Our position iterations")
      ->delimiter(',')
      ->check(CLI::Range(1, 64));
  app.add_option("--velocity-iterations", velocity_iterations,
                 "Our velocity iterations (default: the server's)")
      ->delimiter(',')
      ->check(CLI::Range(1, 64));
  app.add_option("--sleep", sleep,
                 "Sleeping on all engines: on, off, both, or auto (both where it matters)")
      ->check(CLI::IsMember({"on", "off", "both", "auto"}));
  app.add_flag("--quick", mode.quick, "Fewer steps on the long scenes (a run of a few minutes)");
  app.add_option("--rain-count", mode.rain_count,
                 "Circles in the rain scenes (rain-N, pile-rain-N-muF)")
      ->check(CLI::Range(1, 1000000));
  app.add_option("--pile-friction", mode.pile_friction,
                 "Contact friction of the pile rain, one scene each (pile-rain-N-muF)")
      ->delimiter(',')
      ->check(bench::finite_range("friction", 0.0, 100.0));
  app.add_flag("--full-grid", grid.full_grid_on_large,
               "Run the whole settings grid on the large scenes too (slow)");
  app.add_flag("--peers-everywhere", grid.peers_on_all_scenes,
               "Run the peers on every scene, not only rain and pyramid");
  app.add_flag("--relaxed-position-passes", grid.relaxed_position_passes,
               "Ours: later position passes update pairs linearly (WorldSettings::"
               "relaxed_position_passes)");
  app.add_option("--csv", csv_path, "Write the CSV here instead of stdout");
  app.add_option("--ratios", ratios_path, "Write peer/ours time ratios (CSV) here");
  app.add_option("--timeline", timeline_path,
                 "Write each run's time per step and awake bodies over simulated time (CSV) here");
  app.add_option("--timeline-window", grid.timeline_steps, "Steps per row of --timeline")
      ->check(CLI::Range(1, 1000000));
  app.add_option("--interleave", grid.interleave_steps,
                 "The runs of a scene take turns of N steps, so that a drift of the machine's "
                 "speed slows every engine alike (0: one run after another)")
      ->check(CLI::Range(0, 1000000));
  app.add_flag("--list", list, "List the scenes and exit");
  if (const auto exit_code = bench::parse_flags(app, argc, argv)) return *exit_code;

  const std::vector<bench::SceneEntry> catalog = bench::scene_catalog(mode);
  if (list) {
    for (const bench::SceneEntry& entry : catalog) std::cout << entry.name << '\n';
    return 0;
  }
  std::vector<bench::SceneEntry> scenes;
  for (const bench::SceneEntry& entry : catalog) {
    if (selected(entry.name, scene_names)) scenes.push_back(entry);
  }
  if (scenes.empty()) {
    std::cerr << "physics-bench: no scene matches --scenes (see --list)\n";
    return 2;
  }
  for (const std::string& name : engine_names) {
    const auto kind = bench::engine_from_string(name);
    if (!kind) {
      std::cerr << "physics-bench: unknown engine '" << name
                << "' (ours, baseline, box2d, chipmunk)\n";
      return 2;
    }
    if (!bench::engine_available(*kind)) {
      std::cerr << "physics-bench: " << name << " is not built in ("
                << (*kind == bench::EngineKind::Baseline
                        ? "configure with -DPHYSICS_BASELINE_CORE=DIR"
                        : "not found at configure time")
                << "); skipped\n";
      continue;
    }
    grid.engines.push_back(*kind);
  }
  for (const std::string& name : integrator_names) {
    const auto integrator = integrator_from_string(name);
    if (!integrator) {
      std::cerr << "physics-bench: unknown integrator '" << name << "'\n";
      return 2;
    }
    grid.integrators.push_back(*integrator);
  }
  grid.substeps = substeps;
  grid.iterations = iterations;
  grid.velocity_iterations = velocity_iterations;
  if (sleep == "on") grid.sleep_modes = {true};
  if (sleep == "off") grid.sleep_modes = {false};
  if (sleep == "both") grid.sleep_modes = {true, false};

  std::ofstream csv_file;
  if (!csv_path.empty() && !open_output(csv_file, csv_path)) return 1;
  std::ostream& csv = csv_path.empty() ? std::cout : csv_file;
  bench::absorb_peer_banners();  // before the CSV's first line on stdout
  // Every output is opened before the first run: a bad path fails at once, not
  // after a run of many minutes.
  std::ofstream ratios;
  if (!ratios_path.empty() && !open_output(ratios, ratios_path)) return 1;
  std::ofstream timeline;
  if (!timeline_path.empty()) {
    if (!open_output(timeline, timeline_path)) return 1;
    bench::write_timeline_header(timeline);
  }
  say_where_peers_do_not_run(scenes, grid);
  bench::write_csv_header(csv);
  std::vector<bench::RunRow> rows;
  try {
    bench::run_grid(scenes, mode, grid, [&](const bench::RunRow& row) {
      bench::write_csv_row(csv, row);
      bench::write_summary(std::cerr, row);
      if (timeline.is_open()) {
        bench::write_timeline_rows(timeline, row);
      }
      rows.push_back(row);
    });
  } catch (const std::exception& error) {
    std::cerr << "physics-bench: " << error.what() << '\n';
    return 1;
  }
  if (ratios.is_open()) {
    bench::write_ratios(ratios, rows);
  } else {
    std::cerr << "\npeer time / our time (same run):\n";
    bench::write_ratios(std::cerr, rows);
  }
  return 0;
}
