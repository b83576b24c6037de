#pragma once
// The tick numbers of a snapshot's relayed ticks (ENCODING_INPUTS, docs/PROTOCOL.md
// 5.12). The server leaves RelayTick.tick out: the ticks a snapshot relays follow one
// another and the last is Snapshot.tick, so each one's number is implied by its
// place. A reader that wants them written in calls number_relay_ticks first.
#include <cstdint>

#include "wire.pb.h"

namespace wire {

// The number of the snapshot's relayed tick at `index`: its own when it carries one,
// else implied by its place (the last is snapshot.tick(), each one before it one
// less; 0 when that would be before tick 0, which no relay holds).
std::uint64_t relay_tick_number(const physics::wire::Snapshot& snapshot, int index);

// Writes every relayed tick's number in (relay_tick_number).
void number_relay_ticks(physics::wire::Snapshot& snapshot);

// Leaves every relayed tick's number out (the server, before it sends a snapshot).
void omit_relay_tick_numbers(physics::wire::Snapshot& snapshot);

}  // namespace wire
