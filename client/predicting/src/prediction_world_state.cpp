// The worlds that arrive as bytes (phys::World::from_bytes): the Welcome's, to
// start from, and a full state's, to start again from.
#include <string>
#include <utility>

#include "client/prediction_core.h"
#include "prediction_rules.h"

namespace client {

bool PredictionCore::start(const Welcome& welcome) {
  if (welcome.tick_rate <= 0.0) {
    fail("the Welcome gives no tick rate");
    return false;
  }
  std::string why;
  auto world = phys::World::from_bytes(welcome.world_state, &why);
  if (!world) {
    ++stats_.bad_world_states;
    fail(welcome.world_state.empty() ? std::string("the Welcome holds no world (want_world)")
                                     : "the Welcome's world does not parse: " + why);
    return false;
  }
  if (rules_ && !welcome.rules_run_here) {
    fail(
        "the server does not run the game's rules for this client (Welcome.rules_run_here): "
        "it runs no rules, or is an older version");
    return false;
  }
  start(std::move(*world), welcome.current_tick, welcome.spectator ? 0 : welcome.body_id,
        welcome.tick_rate, welcome.max_acceleration, welcome.players,
        welcome.spectator ? 0 : welcome.client_id);
  return true;
}

void PredictionCore::apply_world_state(std::uint64_t tick, std::span<const std::uint8_t> bytes,
                                       const std::vector<Player>& players) {
  std::string why;
  auto world = phys::World::from_bytes(bytes, &why);
  if (!world) {
    ++stats_.bad_world_states;
    const std::string what =
        "the full state of tick " + std::to_string(tick) + " does not parse: " + why;
    if (++failed_resyncs_ >= config_.max_failed_resyncs) {
      fail(what + ", " + std::to_string(failed_resyncs_) + " times in a row");
      return;
    }
    // Asked again: the server answers each request with the world as it is then.
    error_ = what;
    awaiting_full_state_ = true;
    request_due_ = true;
    ++stats_.full_state_requests;
    return;
  }
  // The prediction as it was shown, compared with the new one at the same tick.
  if (world_tick_ >= tick) {
    compare_ = positions();
    compare_tick_ = world_tick_;
  }
  if (rules_ && rules_->wants_contact_events()) world->set_contact_events(true);
  begin(std::move(*world), tick);
  reset_players(players);
  matched_since_resync_ = false;
  ++stats_.resyncs;
}

}  // namespace client
