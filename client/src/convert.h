#pragma once
// Wire messages (physics.wire) to the client's plain structs and back. Private to
// the library: callers see only client/types.h.
#include "client/types.h"
#include "wire.pb.h"

namespace client::convert {

Welcome from_wire(const physics::wire::Welcome& message);
// The snapshot's header and shapes; the bodies come from the client's reconstruction.
Snapshot header_from_wire(const physics::wire::Snapshot& message);
View from_wire(const physics::wire::ViewRequest& message);
physics::wire::ViewRequest to_wire(const ViewRequest& request);
ServerError from_wire(const physics::wire::Error& message);
Pong from_wire(const physics::wire::Pong& message);
BodyShape from_wire(const physics::wire::BodyShape& message);

physics::wire::ClientMessage make_hello(std::uint32_t protocol_version, const std::string& name,
                                        const std::string& token, const ViewRequest& view,
                                        bool spectate, std::optional<std::uint32_t> seat);
void set_contacts(physics::wire::Hello& hello, const ContactSubscription& contacts);
physics::wire::ClientMessage make_ack(std::uint64_t tick);
physics::wire::ClientMessage make_full_state_request();
physics::wire::ClientMessage make_input(std::uint64_t tick, double ax, double ay,
                                        std::uint64_t sequence);
physics::wire::ClientMessage make_ping(std::uint64_t nonce, std::uint64_t client_time_ns);
physics::wire::ClientMessage make_bye(const std::string& reason);

}  // namespace client::convert
