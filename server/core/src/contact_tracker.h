#pragma once
// Contact events (physics/contact_events.h) from the touches the step notes: the
// pairs in contact are kept from step to step, sorted, and each step's touches are
// merged into them, begins and ends coming out in that order. The merge reads no
// body but those of the pairs that end: a pair's generations come with its touch,
// and removals are told.
#include <cstdint>
#include <vector>

#include "physics/contact_events.h"

namespace phys {

struct Body;

class ContactTracker {
 public:
  // Forgets every contact and event (events switched off, or on afresh).
  void clear();
  // Before a step's first sub-step.
  void begin_step();
  // The sub-step moved these slots (awake bodies): their contacts are judged.
  void mark_stepped(const std::vector<std::uint32_t>& slots, std::size_t slot_count);
  // A pair seen touching, each body by slot and generation; normal from a toward b,
  // closing speed positive when they approach. The first touch of a pair in a step
  // is the one kept.
  void note(BodyId a, BodyId b, Vec2 point, Vec2 normal, double closing);
  // The body in `slot` was removed: its contacts end at the next finish.
  void removed(std::uint32_t slot);
  // After the step's last sub-step: this step's events (in pair order). Returns
  // how many.
  std::size_t finish(std::uint64_t step, const std::vector<Body>& bodies);

  const std::vector<ContactEvent>& events() const { return events_; }
  std::size_t contact_count() const { return current_.size(); }
  // Whether the removals carried over are as removed() leaves them in a world of
  // `slots` body slots: each removed slot listed once and flagged, no other slot
  // flagged (world_bytes.cpp checks what it reads; finish clears the flags by the
  // list).
  bool removals_consistent(std::size_t slots) const;
  // Walks what carries over between steps, for World::to_bytes and from_bytes
  // (world_bytes.cpp, the only user).
  template <class A>
  void state_fields(A& a);
  // Heap bytes of what carries over between steps (World::save copies it).
  std::size_t state_bytes() const {
    return current_.capacity() * sizeof(Contacting) + stepped_.capacity() * sizeof(std::uint64_t);
  }

 private:
  // A pair: its slots (a below b) in one key, then its generations.
  struct Pair {
    std::uint64_t slots;  // a << 32 | b
    std::uint32_t generation_a;
    std::uint32_t generation_b;
    BodyId a() const { return {static_cast<std::uint32_t>(slots >> 32), generation_a}; }
    BodyId b() const { return {static_cast<std::uint32_t>(slots), generation_b}; }
    bool operator<(const Pair& o) const {
      if (slots != o.slots) return slots < o.slots;
      if (generation_a != o.generation_a) return generation_a < o.generation_a;
      return generation_b < o.generation_b;
    }
    bool operator==(const Pair&) const = default;
  };
  struct Touch {
    Pair pair;
    std::uint32_t order;  // when it was noted in the step
    Vec2 point;
    Vec2 normal;
    double closing;
  };
  struct Contacting {
    Pair pair;
    Vec2 point;
    Vec2 normal;
  };
  struct Keyed {
    std::uint64_t slots;
    std::uint32_t index;  // into touches_
  };

  bool stepped(std::uint32_t slot) const {
    return slot < stepped_.size() && stepped_[slot] == serial_;
  }
  bool was_removed(std::uint32_t slot) const {
    return slot < removed_flag_.size() && removed_flag_[slot] != 0;
  }

  std::vector<Touch> touches_;              // this step's, in the order noted
  std::vector<Keyed> order_;                // finish's: the first touch of each pair, in pair order
  std::vector<Contacting> current_;         // in contact after the last step, in pair order
  std::vector<Contacting> next_;            // finish's scratch
  std::vector<ContactEvent> events_;        // the last step's
  std::vector<std::uint64_t> stepped_;      // per slot: the serial of the last step it moved in
  std::uint64_t serial_ = 0;                // steps begun since the last clear, from 1
  std::vector<std::uint8_t> removed_flag_;  // per slot: removed since the last finish
  std::vector<std::uint32_t> removed_;      // those slots
};

}  // namespace phys
