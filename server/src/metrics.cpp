#include "metrics.h"

#include <algorithm>
#include <charconv>
#include <sstream>

namespace server {
namespace {

// The shortest text that reads back as the same double (6.25e-05, 0.25).
std::string number(double value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

void header(std::ostringstream& out, const char* name, const char* type, const char* help) {
  out << "# HELP " << name << ' ' << help << "\n# TYPE " << name << ' ' << type << '\n';
}

void counter(std::ostringstream& out, const char* name, const char* help, std::uint64_t value) {
  header(out, name, "counter", help);
  out << name << ' ' << value << '\n';
}

void gauge(std::ostringstream& out, const char* name, const char* help, double value) {
  header(out, name, "gauge", help);
  out << name << ' ' << number(value) << '\n';
}

// Label values are our own fixed strings (drop reasons); spaces and parentheses
// are fine inside quotes, and none holds a quote or a backslash.
std::string reason_label(DropReason reason) {
  std::string text = to_string(reason);
  std::replace(text.begin(), text.end(), ' ', '_');
  text.erase(std::remove_if(text.begin(), text.end(), [](char c) { return c == '(' || c == ')'; }),
             text.end());
  return text;
}

}  // namespace

std::string render_prometheus(const ServerStats& s, const MetricsInfo& info) {
  std::ostringstream out;
  counter(out, "physics_ticks_total", "Ticks stepped.", s.ticks_stepped);
  gauge(out, "physics_current_tick", "The last tick stepped.", static_cast<double>(s.current_tick));
  gauge(out, "physics_tick_rate_hz", "Ticks per second of the fixed timestep.", info.tick_rate);

  header(out, "physics_tick_seconds", "histogram",
         "Wall time of one tick: the step and the snapshot encoding.");
  std::uint64_t cumulative = 0;
  for (std::size_t i = 0; i < kTickSecondsBounds.size(); ++i) {
    cumulative += s.tick_seconds_buckets[i];
    out << "physics_tick_seconds_bucket{le=\"" << number(kTickSecondsBounds[i]) << "\"} "
        << cumulative << '\n';
  }
  cumulative += s.tick_seconds_buckets.back();
  out << "physics_tick_seconds_bucket{le=\"+Inf\"} " << cumulative << '\n';
  out << "physics_tick_seconds_sum " << number(s.total_tick_seconds) << '\n';
  out << "physics_tick_seconds_count " << cumulative << '\n';
  gauge(out, "physics_tick_seconds_max", "The longest tick so far.", s.max_tick_seconds);

  counter(out, "physics_tick_overruns_total", "Ticks that took longer than one tick period.",
          s.tick_overruns);
  counter(out, "physics_dropped_steps_total",
          "Steps the fixed timestep threw away after falling behind.", s.dropped_steps);

  const std::size_t pending =
      s.open_connections -
      std::min(s.open_connections, s.connected_clients + s.spectators + s.lobby_clients);
  header(out, "physics_clients", "gauge", "Open connections by state.");
  out << "physics_clients{state=\"pending\"} " << pending << '\n';
  out << "physics_clients{state=\"lobby\"} " << s.lobby_clients << '\n';
  out << "physics_clients{state=\"playing\"} " << s.connected_clients << '\n';
  out << "physics_clients{state=\"spectating\"} " << s.spectators << '\n';
  gauge(out, "physics_max_clients", "Most players at once.", static_cast<double>(info.max_clients));
  counter(out, "physics_connections_accepted_total", "TCP connections accepted.",
          s.connections_accepted);

  counter(out, "physics_bytes_sent_total", "Bytes written to clients.", s.bytes_sent);
  counter(out, "physics_bytes_received_total", "Bytes read from clients.", s.bytes_received);

  header(out, "physics_sessions_ended_total", "counter", "Sessions ended, by reason.");
  for (const auto& [reason, count] : s.dropped) {
    out << "physics_sessions_ended_total{reason=\"" << reason_label(reason) << "\"} " << count
        << '\n';
  }

  counter(out, "physics_lockstep_timeouts_total",
          "Lockstep ticks stepped after a timeout, with missing inputs reused.",
          s.lockstep_timeouts);
  counter(out, "physics_reused_inputs_total", "Missing lockstep inputs replaced by the last one.",
          s.reused_inputs);
  counter(out, "physics_snapshots_sent_total", "Snapshots sent.", s.snapshots_sent);
  counter(out, "physics_snapshots_skipped_total",
          "Due snapshots not sent because the client's window was full.", s.skipped_snapshots);
  counter(out, "physics_late_inputs_total", "Inputs applied at the next tick instead.",
          s.late_inputs);
  counter(out, "physics_clamped_inputs_total", "Inputs clamped to the scene's max acceleration.",
          s.clamped_inputs);
  counter(out, "physics_invalid_inputs_total", "Inputs with NaN or infinite values.",
          s.invalid_inputs);
  gauge(out, "physics_up", "1 while the server runs, 0 once it shuts down.",
        s.shutting_down ? 0.0 : 1.0);
  return out.str();
}

Readiness readiness(const ServerStats& stats, const MetricsInfo& info,
                    std::chrono::steady_clock::time_point now) {
  if (stats.shutting_down) return {false, "shutting down"};
  if (info.lockstep) {
    return {true, stats.lockstep_started ? "lockstep: stepping as inputs arrive"
                                         : "lockstep: waiting for players"};
  }
  if (stats.ticks_stepped == 0) return {false, "no tick stepped yet"};
  const double period = 1.0 / info.tick_rate;
  const double allowed = std::max(1.0, 10.0 * period);
  const double since = std::chrono::duration<double>(now - stats.last_tick_at).count();
  if (since > allowed) {
    return {false, "last tick " + number(since) + " s ago (allowed " + number(allowed) + " s)"};
  }
  if (stats.last_tick_seconds > period) {
    return {false, "overrunning: the last tick took " + number(stats.last_tick_seconds) +
                       " s, over its period of " + number(period) + " s"};
  }
  return {true, "stepping on time"};
}

}  // namespace server
