#pragma once
// Inputs filed by the tick they apply at, one buffer per client, and the checks an
// input passes before it is filed. No sockets and no clock: tests drive it directly.
#include <cstddef>
#include <cstdint>
#include <deque>

#include "physics/vec2.h"

namespace server {

enum class InputVerdict : std::uint8_t {
  OnTime,       // filed at the tick it names
  Late,         // its tick was already stepped: filed at the next tick, and counted
  NonFinite,    // NaN or infinite acceleration: dropped
  TooFarAhead,  // tick beyond current + max_ticks_ahead: dropped
  NotJoined,    // the client has no body (never joined, or left): dropped
};

struct InputCheck {
  InputVerdict verdict = InputVerdict::OnTime;
  phys::Vec2 acceleration{};  // clamped to the limit
  bool clamped = false;
  std::uint64_t apply_at = 0;  // the tick it will be applied at (valid when filed)
  bool accepted() const { return verdict == InputVerdict::OnTime || verdict == InputVerdict::Late; }
};

// The magnitude is clamped by phys::clamp_length, the one overflow-safe clamp.
// `current_tick` is the last tick stepped; the next one is current_tick + 1.
InputCheck check_input(std::uint64_t tick, phys::Vec2 acceleration, std::uint64_t current_tick,
                       std::uint64_t max_ticks_ahead, double max_acceleration);

// One client's inputs. Each tick holds at most one input, so a client can never
// buffer more than max_ticks_ahead + 1 of them. They sit in one slot a tick, from
// the oldest pending tick to the newest (sizeof(Slot), 32 bytes, a tick of that
// span, empty ticks included), in blocks that are freed as the ticks are taken:
// the memory of a full window comes back once its ticks have passed.
class ClientInputs {
 public:
  // Files an accepted input. At one tick, the input naming the later tick wins
  // (an on-time input beats a late one refiled there); equal names: the newest.
  void file(std::uint64_t apply_at, std::uint64_t named_tick, phys::Vec2 acceleration);
  bool has_input_for(std::uint64_t tick) const;
  bool has_any_input() const { return pending_ > 0; }

  struct Taken {
    phys::Vec2 acceleration{};  // what the body holds from this tick on
    bool fresh = false;         // an input was due at this tick (else the held one)
  };
  // Consumes every input due at or before `tick`; the newest becomes the held one.
  Taken take(std::uint64_t tick);

  phys::Vec2 held() const { return held_; }
  // The tick named by the newest input applied (the client's own numbering).
  std::uint64_t last_applied_tick() const { return last_applied_tick_; }
  bool has_applied() const { return has_applied_; }
  std::size_t pending_count() const { return pending_; }
  // The bytes the pending inputs hold now: one slot a tick of their span.
  std::size_t memory_bytes() const { return slots_.size() * sizeof(Slot); }

 private:
  struct Slot {
    std::uint64_t named_tick = 0;
    phys::Vec2 acceleration{};
    bool present = false;
  };
  // slots_[i] is tick first_tick_ + i. The first slot always holds an input (or
  // there are none), so the front is the earliest pending input.
  std::deque<Slot> slots_;
  std::uint64_t first_tick_ = 0;
  std::size_t pending_ = 0;
  std::size_t peak_slots_ = 0;  // the largest span since the deque was last renewed
  phys::Vec2 held_{};
  std::uint64_t last_applied_tick_ = 0;
  bool has_applied_ = false;
};

}  // namespace server
