#pragma once
// The lines physics-client prints: one per snapshot (text or JSON), the Welcome,
// and the load report.
#include <string>

#include "client/load.h"
#include "client/types.h"

namespace client_app {

std::string format_welcome(const client::Welcome& welcome, bool json);
// `with_hash`: the view asked for the state hash (--state-hash). Text leaves the hash
// out otherwise (it would read 0000000000000000); JSON always has the field.
std::string format_snapshot(const client::Snapshot& snapshot, bool json, bool with_hash);
// One line per contact event (--contacts).
std::string format_contact_event(const client::ContactEvent& event, bool json);
// One line per game message received: the payload as text when it is well-formed
// UTF-8, else as base64 ("base64" in JSON, "(base64)" in text).
std::string format_game_message(const client::GameMessage& message, bool json);
std::string format_load_report(const client::LoadReport& report, bool json);

}  // namespace client_app
