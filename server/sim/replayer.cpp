#include "replayer.h"

#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "scene/scene.h"
#include "server/recorded_scene.h"

namespace replay {
namespace {

namespace rec = physics::recording;

// hash_every is bounded so that a record's tick can be at most this far ahead of
// the replay: a corrupted tick cannot make the replay step for hours.
constexpr std::uint64_t kMaxHashEvery = 65535;

std::string describe_body(std::uint64_t packed) {
  const phys::BodyId id = phys::BodyId::from_packed(packed);
  return "body " + std::to_string(packed) + " (index " + std::to_string(id.index) +
         ", generation " + std::to_string(id.generation) + ")";
}

}  // namespace

Replayer::Opened Replayer::open(const std::filesystem::path& path,
                                std::shared_ptr<server::GameRules> rules) {
  recording::RecordingReader::Opened opened = recording::RecordingReader::open(path);
  if (auto* error = std::get_if<recording::RecordingError>(&opened)) return *error;
  return from_reader(std::get<std::unique_ptr<recording::RecordingReader>>(std::move(opened)),
                     std::move(rules));
}

Replayer::Opened Replayer::from_bytes(std::string bytes, std::shared_ptr<server::GameRules> rules) {
  recording::RecordingReader::Opened opened =
      recording::RecordingReader::from_bytes(std::move(bytes));
  if (auto* error = std::get_if<recording::RecordingError>(&opened)) return *error;
  return from_reader(std::get<std::unique_ptr<recording::RecordingReader>>(std::move(opened)),
                     std::move(rules));
}

Replayer::Opened Replayer::from_reader(std::unique_ptr<recording::RecordingReader> reader,
                                       std::shared_ptr<server::GameRules> rules) {
  const std::uint64_t at = reader->header_offset();
  const auto refuse = [at](std::string message) {
    return recording::RecordingError{at, "header: " + std::move(message)};
  };
  if (!reader->header().has_server()) {
    return refuse("a client recording (what a client received) cannot be replayed");
  }
  const rec::ServerRun& run = reader->header().server();
  if (!run.has_scene()) return refuse("no scene");
  if (run.hash_every() == 0 || run.hash_every() > kMaxHashEvery) {
    return refuse("hash_every " + std::to_string(run.hash_every()) + " is not in [1, " +
                  std::to_string(kMaxHashEvery) + "]");
  }
  // Checked here, not only by Simulation, which would take 0 for the scene's rate.
  if (std::string problem = scene::tick_rate_problem(run.tick_rate()); !problem.empty()) {
    return refuse(problem);
  }
  std::variant<scene::SceneDef, std::string> scene = server::from_recorded(run.scene());
  if (auto* message = std::get_if<std::string>(&scene)) return refuse(*message);
  server::SimulationOptions options;
  options.tick_rate = run.tick_rate();
  options.max_ticks_ahead = run.max_ticks_ahead();
  std::unique_ptr<server::Simulation> simulation;
  try {
    simulation = std::make_unique<server::Simulation>(std::get<scene::SceneDef>(std::move(scene)),
                                                      options, std::move(rules));
  } catch (const std::invalid_argument& error) {
    return refuse(error.what());
  }
  std::unique_ptr<Replayer> replayer(new Replayer(std::move(reader), std::move(simulation)));
  replayer->hash_every_ = run.hash_every();
  return replayer;
}

Replayer::Replayer(std::unique_ptr<recording::RecordingReader> reader,
                   std::unique_ptr<server::Simulation> simulation)
    : reader_(std::move(reader)), simulation_(std::move(simulation)) {}

Replayer::Step Replayer::bad(std::string message) {
  error_ = recording::RecordingError{reader_->record_offset(), std::move(message)};
  return Step::BadFile;
}

bool Replayer::peek() {
  if (has_next_) return true;
  if (at_end_) return false;
  switch (reader_->next(next_)) {
    case recording::RecordingReader::Next::Record:
      has_next_ = true;
      return true;
    case recording::RecordingReader::Next::End:
      at_end_ = true;
      return false;
    case recording::RecordingReader::Next::Error:
      error_ = reader_->error();
      return false;
  }
  return false;
}

// Applies a join, leave or input due now; false (error_ set) when it cannot be.
bool Replayer::apply(const rec::Record& record) {
  server::Simulation& sim = *simulation_;
  const auto fail = [this](std::string message) {
    error_ = recording::RecordingError{reader_->record_offset(), std::move(message)};
    return false;
  };
  switch (record.kind_case()) {
    case rec::Record::kJoin: {
      const rec::Join& join = record.join();
      if (sim.body_of(join.client())) {
        return fail("join of client " + std::to_string(join.client()) + ", already in the room");
      }
      std::optional<std::uint32_t> seat;
      if (join.has_seat()) seat = join.seat();
      const std::optional<phys::BodyId> body = sim.join(join.client(), seat);
      if (!body || body->packed() != join.body()) {
        pending_join_mismatches_.push_back(
            "client " + std::to_string(join.client()) + " joined after tick " +
            std::to_string(join.tick()) + " with " + describe_body(join.body()) +
            " in the recording, " + (body ? describe_body(body->packed()) : "no body") +
            " in the replay");
      }
      return true;
    }
    case rec::Record::kLeave: {
      const rec::Leave& leave = record.leave();
      if (!sim.leave(leave.client()) && !diverged_) {
        return fail("leave of client " + std::to_string(leave.client()) + ", not in the room");
      }
      return true;
    }
    case rec::Record::kInput: {
      const rec::Input& input = record.input();
      const phys::Vec2 a{input.ax(), input.ay()};
      if (!phys::is_finite(a)) return fail("input acceleration is not finite");
      if (!sim.file_recorded_input(input.client(), input.tick(), a) && !diverged_) {
        return fail("input of client " + std::to_string(input.client()) + ", not in the room");
      }
      return true;
    }
    case rec::Record::kGameMessage: {
      const rec::GameMessage& message = record.game_message();
      if (!sim.file_recorded_game_message(message.client(), message.tick(), message.payload()) &&
          !diverged_) {
        return fail("game message of client " + std::to_string(message.client()) +
                    ", not in the room");
      }
      return true;
    }
    default:
      return fail("a client's record (Received) in a server recording");
  }
}

Replayer::Step Replayer::step() {
  server::Simulation& sim = *simulation_;
  const std::uint64_t now = sim.current_tick();
  const std::uint64_t next_tick = now + 1;
  // Joins and leaves recorded after tick `now`, and inputs for `next_tick`.
  for (;;) {
    if (!peek()) {
      if (!at_end_) return Step::BadFile;
      break;
    }
    std::uint64_t due = 0;  // the tick the replay must have stepped before it applies
    switch (next_.kind_case()) {
      case rec::Record::kJoin:
        due = next_.join().tick();
        break;
      case rec::Record::kLeave:
        due = next_.leave().tick();
        break;
      case rec::Record::kInput:
        if (next_.input().tick() == 0) return bad("input for tick 0 (ticks start at 1)");
        due = next_.input().tick() - 1;
        break;
      case rec::Record::kGameMessage:
        if (next_.game_message().tick() == 0) return bad("game message for tick 0");
        due = next_.game_message().tick() - 1;
        break;
      case rec::Record::kTickHash:
        if (next_.tick_hash().tick() == 0) return bad("hash of tick 0 (ticks start at 1)");
        due = next_.tick_hash().tick() - 1;
        break;
      default:
        return bad("a client's record (Received) in a server recording");
    }
    if (due < now) {
      return bad("record for tick " + std::to_string(due) + " after tick " + std::to_string(now) +
                 " was stepped (out of order)");
    }
    if (due - now > hash_every_) {
      return bad("record jumps from tick " + std::to_string(now) + " to " + std::to_string(due) +
                 ", but hashes are recorded every " + std::to_string(hash_every_) + " ticks");
    }
    if (due > now || next_.kind_case() == rec::Record::kTickHash) break;
    if (!apply(next_)) return Step::BadFile;
    has_next_ = false;
  }
  if (!has_next_ && at_end_) return Step::End;

  check_ = TickCheck{};
  check_.join_mismatches = std::exchange(pending_join_mismatches_, {});
  sim.step_tick();
  check_.tick = next_tick;
  if (has_next_ && next_.kind_case() == rec::Record::kTickHash &&
      next_.tick_hash().tick() == next_tick) {
    compare(next_.tick_hash());
    has_next_ = false;
  }
  if (check_.diverged()) diverged_ = true;
  return Step::Stepped;
}

void Replayer::compare(const rec::TickHash& hash) {
  const phys::World& world = simulation_->world();
  check_.hash_recorded = true;
  check_.recorded_hash = hash.state_hash();
  check_.replayed_hash = world.state_hash();
  if (hash.body_ids_size() == 0 && hash.body_hashes_size() == 0) return;
  check_.body_hashes_recorded = true;
  // Mismatched lists are reported as a difference of every body listed, not trusted.
  std::map<std::uint64_t, std::uint64_t> recorded;
  const int listed = std::min(hash.body_ids_size(), hash.body_hashes_size());
  for (int i = 0; i < listed; ++i) recorded.emplace(hash.body_ids(i), hash.body_hashes(i));
  world.for_each_body([&](const phys::BodyState& body) {
    if (body.motion != phys::Motion::Dynamic) return;
    const auto it = recorded.find(body.id.packed());
    if (it == recorded.end()) {
      check_.bodies.push_back({body.id.packed(), BodyDifference::Kind::OnlyInReplay, body});
      return;
    }
    if (it->second != server::body_hash(body)) {
      check_.bodies.push_back({body.id.packed(), BodyDifference::Kind::Differs, body});
    }
    recorded.erase(it);
  });
  for (const auto& [id, ignored] : recorded) {
    check_.bodies.push_back({id, BodyDifference::Kind::OnlyInRecording, std::nullopt});
  }
}

ReplayReport check_recording(Replayer& replayer) {
  ReplayReport report;
  for (;;) {
    const Replayer::Step step = replayer.step();
    if (step == Replayer::Step::BadFile) {
      // A divergence already found stands; the bodies then go unnamed.
      if (report.outcome == ReplayReport::Outcome::Diverged) return report;
      report.outcome = ReplayReport::Outcome::BadFile;
      report.error = replayer.error();
      return report;
    }
    if (step == Replayer::Step::End) return report;
    const TickCheck& check = replayer.last_check();
    ++report.ticks;
    report.last_tick = check.tick;
    if (report.outcome == ReplayReport::Outcome::Equal) {
      if (!check.diverged()) {
        if (check.hash_recorded) ++report.hashes_checked;
        continue;
      }
      report.outcome = ReplayReport::Outcome::Diverged;
      report.first_difference = check;
    }
    if (check.body_hashes_recorded) {
      report.bodies_tick = check.tick;
      report.bodies = check.bodies;
      return report;
    }
  }
}

ReplayReport check_recording_file(const std::filesystem::path& path) {
  Replayer::Opened opened = Replayer::open(path);
  if (auto* error = std::get_if<recording::RecordingError>(&opened)) {
    ReplayReport report;
    report.outcome = ReplayReport::Outcome::BadFile;
    report.error = *error;
    return report;
  }
  return check_recording(*std::get<std::unique_ptr<Replayer>>(opened));
}

}  // namespace replay
