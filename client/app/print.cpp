#include "print.h"

#include <fmt/format.h>

#include "payload_text.h"
#include "text/json_escape.h"

namespace client_app {

// The scene name comes from the server: escaped, so that any name is one JSON string.
std::string format_welcome(const client::Welcome& welcome, bool json) {
  if (json) {
    return fmt::format(
        "{{\"welcome\":{{\"client_id\":{},\"body_id\":{},\"tick_rate\":{},\"current_tick\":{},"
        "\"bodies\":{},\"lockstep\":{},\"max_acceleration\":{},\"scene\":\"{}\"}}}}",
        welcome.client_id, welcome.body_id, welcome.tick_rate, welcome.current_tick,
        welcome.bodies.size(), welcome.lockstep, welcome.max_acceleration,
        text::json_escape(welcome.scene_name));
  }
  return fmt::format(
      "connected: client {} controls body {} in scene '{}' ({} bodies, {} Hz{}, tick {})",
      welcome.client_id, welcome.body_id, welcome.scene_name, welcome.bodies.size(),
      welcome.tick_rate, welcome.lockstep ? ", lockstep" : "", welcome.current_tick);
}

std::string format_snapshot(const client::Snapshot& snapshot, bool json, bool with_hash) {
  const client::BodyState own = snapshot.own.value_or(client::BodyState{});
  // Doubles are printed in their shortest exact form ({}), so nothing is lost. The
  // hash is a hex string: JSON numbers past 2^53 lose digits in many parsers.
  if (json) {
    return fmt::format(
        "{{\"tick\":{},\"state_hash\":\"{:016x}\",\"own_body\":{},\"has_own\":{},\"x\":{},"
        "\"y\":{},\"vx\":{},\"vy\":{},\"has_applied_input\":{},\"last_applied_input_tick\":{},"
        "\"bodies\":{},\"records\":{},\"wire_bytes\":{},\"in_sync\":{}}}",
        snapshot.tick, snapshot.state_hash, own.body_id, snapshot.own.has_value(), own.position.x,
        own.position.y, own.velocity.x, own.velocity.y, snapshot.has_applied_input,
        snapshot.last_applied_input_tick, snapshot.bodies.size(), snapshot.records,
        snapshot.wire_bytes, snapshot.in_sync);
  }
  const std::string hash = with_hash ? fmt::format(" hash {:016x}", snapshot.state_hash) : "";
  return fmt::format("tick {} pos ({:.6f}, {:.6f}) vel ({:.6f}, {:.6f}){} ({} records, {} bytes)",
                     snapshot.tick, own.position.x, own.position.y, own.velocity.x, own.velocity.y,
                     hash, snapshot.records, snapshot.wire_bytes);
}

std::string format_contact_event(const client::ContactEvent& event, bool json) {
  const char* kind = event.end ? "end" : "begin";
  if (json) {
    return fmt::format(
        "{{\"contact\":\"{}\",\"tick\":{},\"body_a\":{},\"body_b\":{},\"x\":{},\"y\":{},"
        "\"nx\":{},\"ny\":{},\"closing_speed\":{}}}",
        kind, event.tick, event.body_a, event.body_b, event.point.x, event.point.y, event.normal.x,
        event.normal.y, event.closing_speed);
  }
  return fmt::format(
      "contact {} tick {} bodies {} {} at ({:.6f}, {:.6f}) normal ({:.6f}, {:.6f}) closing "
      "{:.6f} m/s",
      kind, event.tick, event.body_a, event.body_b, event.point.x, event.point.y, event.normal.x,
      event.normal.y, event.closing_speed);
}

std::string format_game_message(const client::GameMessage& message, bool json) {
  const bool text = is_utf8(message.payload);
  if (json) {
    return fmt::format("{{\"game_message\":{{\"tick\":{},\"{}\":\"{}\"}}}}", message.tick,
                       text ? "text" : "base64",
                       text ? text::json_escape(message.payload) : base64(message.payload));
  }
  // Text lines stay one line: the payload's control characters are escaped as JSON's.
  return fmt::format("game message tick {}{}: {}", message.tick, text ? "" : " (base64)",
                     text ? text::json_escape(message.payload) : base64(message.payload));
}

std::string format_load_report(const client::LoadReport& report, bool json) {
  if (json) {
    return fmt::format(
        "{{\"bots\":{},\"connected\":{},\"seconds\":{:.3f},\"latency_samples\":{},"
        "\"latency_median_ms\":{:.3f},\"latency_p99_ms\":{:.3f},\"latency_max_ms\":{:.3f},"
        "\"bytes_per_second_mean\":{:.0f},\"bytes_per_second_min\":{:.0f},"
        "\"bytes_per_second_max\":{:.0f},\"snapshots_per_second\":{:.2f},"
        "\"ticks_per_second\":{:.2f},\"input_delay_ticks_median\":{:.1f},"
        "\"input_delay_ticks_final_min\":{},\"input_delay_ticks_final_max\":{},"
        "\"snapshot_age_ms_median\":{:.3f},\"snapshot_age_ms_p99\":{:.3f},"
        "\"late_inputs\":{},\"inputs_sent\":{},"
        "\"inputs_unanswered\":{},\"snapshots_dropped\":{},\"failures\":{},"
        "\"predict\":{},\"own_input_visible_ms_median\":{:.3f},"
        "\"own_input_visible_ms_p99\":{:.3f},\"rollbacks_per_second\":{:.2f},"
        "\"resimulated_ticks_per_second\":{:.2f},\"largest_correction_m\":{:.6f},"
        "\"largest_smoothed_correction_m\":{:.6f},\"desyncs\":{},\"resyncs\":{},"
        "\"frame_cpu_ms_median\":{:.3f},\"frame_cpu_ms_p99\":{:.3f},\"frames\":{},"
        "\"game_messages_sent\":{},\"game_messages_received\":{},"
        "\"own_message_visible_ms_median\":{:.3f},\"own_message_visible_ms_p99\":{:.3f},"
        "\"rules_predicted\":{},\"bytes_per_second\":{:.0f}}}",
        report.bots_requested, report.bots_connected, report.seconds, report.latency_samples,
        report.latency_median_ms, report.latency_p99_ms, report.latency_max_ms,
        report.bytes_per_second_mean, report.bytes_per_second_min, report.bytes_per_second_max,
        report.snapshots_per_second_mean, report.ticks_per_second, report.input_delay_median,
        report.input_delay_min, report.input_delay_max, report.snapshot_age_median_ms,
        report.snapshot_age_p99_ms, report.late_margins, report.inputs_sent,
        report.inputs_unanswered, report.snapshots_dropped, report.failures.size(),
        report.predicting, report.own_input_visible_ms_median, report.own_input_visible_ms_p99,
        report.rollbacks_per_second, report.resimulated_ticks_per_second,
        report.largest_correction_m, report.largest_smoothed_correction_m, report.desyncs,
        report.resyncs, report.frame_cpu_ms_median, report.frame_cpu_ms_p99, report.frames,
        report.game_messages_sent, report.game_messages_received,
        report.own_message_visible_ms_median, report.own_message_visible_ms_p99,
        report.rules_predicted, report.bytes_per_second_mean);
  }
  std::string text = fmt::format(
      "bots {} (connected {}) over {:.2f} s\n"
      "input -> snapshot latency: median {:.3f} ms, p99 {:.3f} ms, max {:.3f} ms ({} samples)\n"
      "received per client: mean {:.0f} B/s (min {:.0f}, max {:.0f}), {:.2f} snapshots/s\n"
      "server ticks {:.2f}/s; input delay median {:.1f} ticks over the run, at the end {} to {}; "
      "newest snapshot age median {:.1f} ms, p99 {:.1f} ms; late inputs {}\n"
      "inputs sent {}, unanswered at the end {}, snapshots dropped by client buffer {}",
      report.bots_requested, report.bots_connected, report.seconds, report.latency_median_ms,
      report.latency_p99_ms, report.latency_max_ms, report.latency_samples,
      report.bytes_per_second_mean, report.bytes_per_second_min, report.bytes_per_second_max,
      report.snapshots_per_second_mean, report.ticks_per_second, report.input_delay_median,
      report.input_delay_min, report.input_delay_max, report.snapshot_age_median_ms,
      report.snapshot_age_p99_ms, report.late_margins, report.inputs_sent, report.inputs_unanswered,
      report.snapshots_dropped);
  text += fmt::format("\ninput -> shown: median {:.3f} ms, p99 {:.3f} ms",
                      report.own_input_visible_ms_median, report.own_input_visible_ms_p99);
  if (report.game_messages_sent > 0 || report.game_messages_received > 0) {
    text += fmt::format("\ngame messages: {} sent, {} received", report.game_messages_sent,
                        report.game_messages_received);
    if (report.predicting) {
      text += fmt::format("; message -> shown ({}): median {:.3f} ms, p99 {:.3f} ms",
                          report.rules_predicted ? "rules predicted" : "confirmed",
                          report.own_message_visible_ms_median, report.own_message_visible_ms_p99);
    }
  }
  if (report.predicting) {
    text += fmt::format(
        "\nprediction: {:.2f} rollbacks/s, {:.2f} ticks stepped again/s, largest correction "
        "{:.6f} m ({:.6f} m a tick after smoothing), desyncs {}, full states {}\n"
        "CPU per rendered frame: median {:.3f} ms, p99 {:.3f} ms ({} frames)",
        report.rollbacks_per_second, report.resimulated_ticks_per_second,
        report.largest_correction_m, report.largest_smoothed_correction_m, report.desyncs,
        report.resyncs, report.frame_cpu_ms_median, report.frame_cpu_ms_p99, report.frames);
  }
  for (const auto& failure : report.failures) text += "\n" + failure;
  return text;
}

}  // namespace client_app
