#pragma once
// Wire messages (physics.wire) to the client's plain structs and back. Private to
// the library: callers see only client/types.h.
#include <cstdint>
#include <vector>

#include "client/client.h"
#include "client/types.h"
#include "wire.pb.h"
#include "wire/reconstruction.h"

namespace client::convert {

Welcome from_wire(const physics::wire::Welcome& message);
// The snapshot's header and shapes; the bodies come from the client's reconstruction.
Snapshot header_from_wire(const physics::wire::Snapshot& message);
View from_wire(const physics::wire::ViewRequest& message);
physics::wire::ViewRequest to_wire(const ViewRequest& request);
ServerError from_wire(const physics::wire::Error& message);
Pong from_wire(const physics::wire::Pong& message);
BodyShape from_wire(const physics::wire::BodyShape& message);

// Keeps `ids` (ascending) to the kinematic bodies among the shapes added and the ids
// removed, so that each snapshot's bodies can say how they move.
void note_kinematic(std::vector<std::uint64_t>& ids, const std::vector<BodyShape>& added,
                    const std::vector<std::uint64_t>& removed);
// The bodies `held` holds, ascending id, each Kinematic when in `kinematic_ids`.
void bodies_held(const wire::Reconstruction& held, const std::vector<std::uint64_t>& kinematic_ids,
                 std::vector<BodyState>& out);

// The Hello this client's config asks for, built by wire::make_hello.
physics::wire::ClientMessage make_hello(const ClientConfig& config);

}  // namespace client::convert
