#pragma once
// Turns the world into bytes once per tick, shared by every session.
//
// A Snapshot differs between clients only in last_applied_input_tick and
// has_applied_input. Protobuf parses concatenated encodings of one message type as
// their merge (scalars: last wins; repeated fields: appended), so the shared part
// (tick, hash, bodies, added, removed) is encoded once per tick and each session
// appends a few bytes of its own fields behind it. Writing that to a socket costs a
// small per-client header and tail, never a copy of the shared bytes (scatter-gather).
#include <cstdint>
#include <memory>
#include <string>

#include "physics/body.h"
#include "physics/world.h"
#include "server/simulation.h"
#include "wire.pb.h"

namespace server {

struct EncodedSnapshot {
  std::uint64_t tick = 0;
  std::uint64_t state_hash = 0;
  // Serialized Snapshot{tick, state_hash, bodies, added, removed}.
  std::string shared;
  // Serialized Snapshot{added, removed} alone: what a session carries into its next
  // snapshot when it has to drop this one unsent (so no add/remove is ever lost).
  std::string changes;
};

std::shared_ptr<const EncodedSnapshot> encode_snapshot(const phys::World& world, std::uint64_t tick,
                                                       const BodyChanges& changes);

// Serialized Snapshot{last_applied_input_tick, has_applied_input}.
std::string encode_client_fields(std::uint64_t last_applied_input_tick, bool has_applied_input);

// The bytes in front of a snapshot frame: varint(frame length), the tag of
// ServerMessage.snapshot, varint(snapshot length). `snapshot_bytes` is the size of
// everything that follows (shared part, carried changes, client fields).
std::string snapshot_frame_header(std::size_t snapshot_bytes);

void fill_body_shape(const phys::BodyState& body, physics::wire::BodyShape& shape);

// The Welcome a client gets after its Hello was accepted.
physics::wire::ServerMessage make_welcome(const Simulation& simulation, std::uint32_t client_id,
                                          phys::BodyId body, bool lockstep);

}  // namespace server
