#include "print_replay.h"

#include <fmt/format.h>

#include <cstdio>

#include "replayer.h"

namespace sim {
namespace {

constexpr int kExitDiverged = 1;
constexpr int kExitBadInput = 2;

std::string hex(std::uint64_t hash) { return fmt::format("{:016x}", hash); }

const char* kind_text(replay::BodyDifference::Kind kind) {
  switch (kind) {
    case replay::BodyDifference::Kind::Differs:
      return "differs";
    case replay::BodyDifference::Kind::OnlyInRecording:
      return "only in the recording";
    case replay::BodyDifference::Kind::OnlyInReplay:
      return "only in the replay";
  }
  return "?";
}

void print_text(const replay::ReplayReport& report) {
  if (report.outcome == replay::ReplayReport::Outcome::Equal) {
    fmt::print("replayed {} ticks (last tick {}): {} recorded hashes, all equal\n", report.ticks,
               report.last_tick, report.hashes_checked);
    return;
  }
  const replay::TickCheck& first = report.first_difference;
  fmt::print("DIVERGED at tick {}", first.tick);
  if (first.hash_recorded && first.recorded_hash != first.replayed_hash) {
    fmt::print(": recorded hash {}, replayed {}", hex(first.recorded_hash),
               hex(first.replayed_hash));
  }
  fmt::print(" ({} earlier hashes equal)\n", report.hashes_checked);
  for (const std::string& mismatch : first.join_mismatches) fmt::print("  {}\n", mismatch);
  if (!report.bodies_tick) {
    fmt::print("no body hashes recorded at or after tick {}: the bodies cannot be named\n",
               first.tick);
    return;
  }
  fmt::print("bodies that differ at tick {} (the first body hashes at or after tick {}): {}\n",
             *report.bodies_tick, first.tick, report.bodies.size());
  for (const replay::BodyDifference& body : report.bodies) {
    const phys::BodyId id = phys::BodyId::from_packed(body.body);
    fmt::print("  body {} (index {}, generation {}): {}", body.body, id.index, id.generation,
               kind_text(body.kind));
    if (body.replayed) {
      fmt::print("; replayed at ({}, {}) moving ({}, {})", body.replayed->position.x,
                 body.replayed->position.y, body.replayed->velocity.x, body.replayed->velocity.y);
    }
    fmt::print("\n");
  }
}

void print_json(const replay::ReplayReport& report) {
  const bool diverged = report.outcome == replay::ReplayReport::Outcome::Diverged;
  fmt::print("{{\"result\":\"{}\",\"ticks\":{},\"last_tick\":{},\"hashes_equal\":{}",
             diverged ? "diverged" : "equal", report.ticks, report.last_tick,
             report.hashes_checked);
  if (diverged) {
    const replay::TickCheck& first = report.first_difference;
    fmt::print(",\"first_tick\":{},\"recorded_hash\":\"{}\",\"replayed_hash\":\"{}\"", first.tick,
               hex(first.recorded_hash), hex(first.replayed_hash));
    if (report.bodies_tick) {
      fmt::print(",\"bodies_tick\":{},\"bodies\":[", *report.bodies_tick);
      for (std::size_t i = 0; i < report.bodies.size(); ++i) {
        fmt::print("{}{}", i == 0 ? "" : ",", report.bodies[i].body);
      }
      fmt::print("]");
    }
  }
  fmt::print("}}\n");
}

}  // namespace

int replay_and_print(const std::string& path, bool json) {
  const replay::ReplayReport report = replay::check_recording_file(path);
  if (report.outcome == replay::ReplayReport::Outcome::BadFile) {
    fmt::print(stderr, "physics-sim: {}: {} (after {} ticks replayed, {} hashes equal)\n", path,
               report.error.to_string(), report.ticks, report.hashes_checked);
    return kExitBadInput;
  }
  if (json) {
    print_json(report);
  } else {
    print_text(report);
  }
  std::fflush(stdout);
  return report.outcome == replay::ReplayReport::Outcome::Equal ? 0 : kExitDiverged;
}

}  // namespace sim
