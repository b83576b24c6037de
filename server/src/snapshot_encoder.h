#pragma once
// The messages around the snapshot feeds: the Welcome, body shapes, and the bytes
// in front of a snapshot frame whose body is written in parts (scatter-gather).
#include <cstdint>
#include <memory>
#include <string>

#include "physics/body.h"
#include "physics/world.h"
#include "server/simulation.h"
#include "wire.pb.h"

namespace server {

// The bytes in front of a snapshot frame: varint(frame length), the tag of
// ServerMessage.snapshot, varint(snapshot length). `snapshot_bytes` is the size of
// everything that follows (the view's shared part, the client's own fields).
std::string snapshot_frame_header(std::size_t snapshot_bytes);
// The same without the frame's length: the tag and varint(snapshot length), the
// ServerMessage's first bytes, for a transport that frames messages its own way.
std::string snapshot_message_header(std::size_t snapshot_bytes);

void fill_body_shape(const phys::BodyState& body, physics::wire::BodyShape& shape);
// The same, with what the world knows beside the state: the body's name and sensor flag.
void fill_body_shape(const phys::BodyState& body, const phys::World& world,
                     physics::wire::BodyShape& shape);

// The Welcome a client gets after its Hello was accepted.
physics::wire::ServerMessage make_welcome(const Simulation& simulation, std::uint32_t client_id,
                                          phys::BodyId body, bool lockstep,
                                          const physics::wire::ViewRequest& view,
                                          std::uint32_t max_players);

}  // namespace server
