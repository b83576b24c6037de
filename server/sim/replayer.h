#pragma once
// A server recording (docs/REPLAY.md) stepped again in-process, one tick at a time:
// the recorded joins, leaves and inputs go into a fresh Simulation of the recorded
// scene, and after each tick the recorded hashes are compared with the world's.
// physics-sim --replay checks a whole file with check_recording(); a viewer steps
// it tick by tick (seeking back means opening it again and stepping forward).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "physics/body.h"
#include "recording.pb.h"
#include "recording/recording_file.h"
#include "server/simulation.h"

namespace replay {

// A body whose hash differs between the recording and the replay.
struct BodyDifference {
  enum class Kind : std::uint8_t { Differs, OnlyInRecording, OnlyInReplay };
  std::uint64_t body = 0;  // phys::BodyId::packed()
  Kind kind = Kind::Differs;
  std::optional<phys::BodyState> replayed;  // the replay's state (absent: OnlyInRecording)
};

// What the recording said about the tick just stepped, against the replay.
struct TickCheck {
  std::uint64_t tick = 0;
  bool hash_recorded = false;
  std::uint64_t recorded_hash = 0;
  std::uint64_t replayed_hash = 0;
  bool body_hashes_recorded = false;
  std::vector<BodyDifference> bodies;  // when body hashes were recorded: those that differ
  // Joins before this tick whose body differs from the recorded one.
  std::vector<std::string> join_mismatches;
  bool diverged() const {
    return (hash_recorded && recorded_hash != replayed_hash) || !join_mismatches.empty() ||
           !bodies.empty();
  }
};

class Replayer {
 public:
  using Opened = std::variant<std::unique_ptr<Replayer>, recording::RecordingError>;
  // Reads the header and builds the recorded scene's world; a client recording, a
  // bad scene or bad run settings are refused with the header's offset.
  // `rules`: the game rules the recorded run had (game_rules.h), run again; a run
  // with rules replayed without them differs at the first tick they changed.
  static Opened open(const std::filesystem::path& path,
                     std::shared_ptr<server::GameRules> rules = nullptr);
  static Opened from_bytes(std::string bytes, std::shared_ptr<server::GameRules> rules = nullptr);
  // Takes an opened reader (the header already read).
  static Opened from_reader(std::unique_ptr<recording::RecordingReader> reader,
                            std::shared_ptr<server::GameRules> rules = nullptr);

  enum class Step : std::uint8_t {
    Stepped,  // one tick stepped; last_check() says how it compares
    End,      // the recording holds nothing more to step
    BadFile,  // error() says what and where
  };
  // Applies the records due before the next tick, steps it, and checks the hashes
  // recorded for it.
  Step step();

  const TickCheck& last_check() const { return check_; }
  const recording::RecordingError& error() const { return error_; }
  const server::Simulation& simulation() const { return *simulation_; }
  std::uint64_t tick() const { return simulation_->current_tick(); }
  const physics::recording::ServerRun& run() const { return reader_->header().server(); }

 private:
  Replayer(std::unique_ptr<recording::RecordingReader> reader,
           std::unique_ptr<server::Simulation> simulation);
  bool peek();
  bool apply(const physics::recording::Record& record);
  void compare(const physics::recording::TickHash& hash);
  Step bad(std::string message);

  std::unique_ptr<recording::RecordingReader> reader_;
  std::unique_ptr<server::Simulation> simulation_;
  physics::recording::Record next_;
  bool has_next_ = false;
  bool at_end_ = false;
  bool diverged_ = false;  // once diverged, records of clients the replay lost are skipped
  std::uint64_t hash_every_ = 1;
  TickCheck check_;
  std::vector<std::string> pending_join_mismatches_;
  recording::RecordingError error_;
};

// A whole recording checked: every recorded hash against the replay, up to the
// first tick that differs; then on to the first body hashes at or after it, to name
// the bodies that differ.
struct ReplayReport {
  enum class Outcome : std::uint8_t { Equal, Diverged, BadFile };
  Outcome outcome = Outcome::Equal;
  std::uint64_t ticks = 0;           // ticks stepped
  std::uint64_t hashes_checked = 0;  // equal ones, before any divergence
  std::uint64_t last_tick = 0;
  TickCheck first_difference;  // Diverged: the first tick that differs
  // Diverged, when body hashes were found at or after it: where, and what differs.
  std::optional<std::uint64_t> bodies_tick;
  std::vector<BodyDifference> bodies;
  recording::RecordingError error;  // BadFile
};

ReplayReport check_recording(Replayer& replayer);
ReplayReport check_recording_file(const std::filesystem::path& path);

}  // namespace replay
