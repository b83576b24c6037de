#include "wire/relay_ticks.h"

namespace wire {

std::uint64_t relay_tick_number(const physics::wire::Snapshot& snapshot, int index) {
  const physics::wire::RelayTick& tick = snapshot.relay(index);
  if (tick.tick() != 0) return tick.tick();
  const std::uint64_t behind = static_cast<std::uint64_t>(snapshot.relay_size() - 1 - index);
  // A snapshot of tick T relays ticks up to T: more than T of them is not a relay.
  return snapshot.tick() >= behind ? snapshot.tick() - behind : 0;
}

void number_relay_ticks(physics::wire::Snapshot& snapshot) {
  for (int i = 0; i < snapshot.relay_size(); ++i) {
    snapshot.mutable_relay(i)->set_tick(relay_tick_number(snapshot, i));
  }
}

void omit_relay_tick_numbers(physics::wire::Snapshot& snapshot) {
  for (physics::wire::RelayTick& tick : *snapshot.mutable_relay()) tick.clear_tick();
}

}  // namespace wire
