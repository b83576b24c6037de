#include "report.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace bench {
namespace {

std::string number(double value) {
  if (std::isnan(value)) return "";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string count(long value) { return value < 0 ? "" : std::to_string(value); }

// Below this our step did nothing worth a ratio: every body asleep (the median step
// of a sleeping pyramid takes 0.1 us, which would read as a ratio of 150,000).
constexpr double kAsleepStepMs = 1.0e-3;

void write_ratio(std::ostream& out, const RunRow& ours, const RunRow& peer, const char* window,
                 double ours_ms, double peer_ms) {
  if (std::isnan(ours_ms) || std::isnan(peer_ms)) return;
  // The ratio's field is left empty (as every missing number in these files).
  const double ratio = ours_ms < kAsleepStepMs ? std::nan("") : peer_ms / ours_ms;
  out << ours.scene << ',' << (ours.sleeping ? "on" : "off") << ',' << window << ','
      << number(ours_ms) << ',' << to_string(peer.engine) << ',' << number(peer_ms) << ','
      << number(ratio) << ',' << number(ours.measures.max_overlap) << ','
      << number(peer.measures.max_overlap) << ',' << number(ours.measures.top_drift) << ','
      << number(peer.measures.top_drift) << '\n';
}

}  // namespace

void write_csv_header(std::ostream& out) {
  out << "scene,engine,integrator,substeps,iterations,sleeping,default,bodies,steps,"
         "ms_median,ms_mean,ms_first,ms_last,cpu_ms_mean,cpu_ms_first,cpu_ms_last,error_name,error,"
         "max_overlap,top_drift,"
         "energy_drift,escaped,non_finite,awake_end,prof_order_and_integrate_ms,prof_candidates_ms,"
         "prof_moves_ms,prof_position_passes_ms,prof_contact_events_ms,prof_velocity_solver_ms,"
         "prof_bounds_and_sleep_ms,notes\n";
}

void write_csv_row(std::ostream& out, const RunRow& row) {
  const Measures& m = row.measures;
  out << row.scene << ',' << to_string(row.engine) << ',' << row.integrator << ',' << row.substeps
      << ',' << row.iterations << ',' << (row.sleeping ? "on" : "off") << ','
      << (row.default_setting ? "yes" : "no") << ',' << row.bodies << ',' << row.steps << ','
      << number(row.ms_median) << ',' << number(row.ms_mean) << ',' << number(row.ms_first) << ','
      << number(row.ms_last) << ',' << number(row.cpu_ms_mean) << ',' << number(row.cpu_ms_first)
      << ',' << number(row.cpu_ms_last) << ',' << m.error_name << ',' << number(m.error) << ','
      << number(m.max_overlap) << ',' << number(m.top_drift) << ',' << number(m.energy_drift) << ','
      << count(m.escaped) << ',' << count(m.non_finite) << ',' << row.awake_end << ',';
  if (row.has_profile) {
    const phys::StepProfile& p = row.profile_mean;
    out << number(p.order_and_integrate * 1e3) << ',' << number(p.candidates * 1e3) << ','
        << number(p.moves * 1e3) << ',' << number(p.position_passes * 1e3) << ','
        << number(p.contact_events * 1e3) << ',' << number(p.velocity_solver * 1e3) << ','
        << number(p.bounds_and_sleep * 1e3) << ',';
  } else {
    out << ",,,,,,,";
  }
  out << m.notes << '\n';
  out.flush();
}

void write_ratios(std::ostream& out, const std::vector<RunRow>& rows) {
  out << "scene,sleeping,window,ours_ms,peer,peer_ms,peer_over_ours,ours_overlap,peer_overlap,"
         "ours_top_drift,peer_top_drift\n";
  for (const RunRow& ours : rows) {
    if (ours.engine != EngineKind::Ours || !ours.default_setting) continue;
    for (const RunRow& peer : rows) {
      if (peer.engine == EngineKind::Ours || peer.scene != ours.scene ||
          peer.sleeping != ours.sleeping) {
        continue;
      }
      // The baseline runs our grid too: its row with the same settings.
      if (runs_our_settings(peer.engine) &&
          (peer.integrator != ours.integrator || peer.substeps != ours.substeps ||
           peer.iterations != ours.iterations)) {
        continue;
      }
      write_ratio(out, ours, peer, "wall_median", ours.ms_median, peer.ms_median);
      write_ratio(out, ours, peer, "wall_mean", ours.ms_mean, peer.ms_mean);
      write_ratio(out, ours, peer, "cpu_mean", ours.cpu_ms_mean, peer.cpu_ms_mean);
      write_ratio(out, ours, peer, "wall_first_window", ours.ms_first, peer.ms_first);
      write_ratio(out, ours, peer, "cpu_first_window", ours.cpu_ms_first, peer.cpu_ms_first);
      write_ratio(out, ours, peer, "wall_last_window", ours.ms_last, peer.ms_last);
      write_ratio(out, ours, peer, "cpu_last_window", ours.cpu_ms_last, peer.cpu_ms_last);
    }
  }
  out.flush();
}

void write_summary(std::ostream& out, const RunRow& row) {
  char text[512];
  std::snprintf(text, sizeof text,
                "%-22s %-8s %-17s sub=%d it=%-6s sleep=%-3s median=%.4g ms mean=%.4g ms "
                "cpu=%.4g ms first=%s last=%s %s=%s",
                row.scene.c_str(), std::string(to_string(row.engine)).c_str(),
                row.integrator.c_str(), row.substeps, row.iterations.c_str(),
                row.sleeping ? "on" : "off", row.ms_median, row.ms_mean, row.cpu_ms_mean,
                number(row.ms_first).c_str(), number(row.ms_last).c_str(),
                row.measures.error_name.c_str(), number(row.measures.error).c_str());
  out << text << '\n';
  if (row.has_profile) {
    const phys::StepProfile& p = row.profile_mean;
    std::snprintf(text, sizeof text,
                  "    profile ms/step: order+integrate %.4f  candidates %.4f  moves %.4f  "
                  "position passes %.4f  contact events %.4f  velocity solver %.4f  "
                  "bounds+sleep %.4f  total %.4f",
                  p.order_and_integrate * 1e3, p.candidates * 1e3, p.moves * 1e3,
                  p.position_passes * 1e3, p.contact_events * 1e3, p.velocity_solver * 1e3,
                  p.bounds_and_sleep * 1e3, p.total * 1e3);
    out << text << '\n';
  }
  out.flush();
}

void write_timeline_header(std::ostream& out) {
  out << "scene,engine,iterations,sleeping,end_s,steps,awake,ms_mean,cpu_ms_mean\n";
}

void write_timeline_rows(std::ostream& out, const RunRow& row) {
  for (const TimelineWindow& w : row.timeline) {
    out << row.scene << ',' << to_string(row.engine) << ',' << row.iterations << ','
        << (row.sleeping ? "on" : "off") << ',' << number(w.end_s) << ',' << w.steps << ','
        << w.awake << ',' << number(w.ms_mean) << ',' << number(w.cpu_ms_mean) << '\n';
  }
  out.flush();
}

}  // namespace bench
