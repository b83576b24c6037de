// The tick loop: the fixed-rate timer without drift, the lockstep gate (and its
// realtime pace and stragglers), one tick stepped and its snapshots handed out.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <string>

#include "log_fields.h"
#include "server_impl.h"
#include "wire/relay_ticks.h"

namespace server {

void Server::Impl::start_fixed_ticks() {
  phys::FixedTimestepConfig timestep_config;
  timestep_config.tick_rate_hz = simulation_.tick_rate();
  timestep_config.max_steps_per_frame =
      config_.steps_per_frame > 0 ? config_.steps_per_frame : simulation_.scene().steps_per_frame;
  timestep_.emplace(clock_, timestep_config);
  next_tick_due_ = clock_.now() + timestep_->period();
  arm_tick_timer();
}

void Server::Impl::arm_tick_timer() {
  tick_timer_.expires_at(next_tick_due_);
  tick_timer_.async_wait([this](std::error_code ec) {
    if (ec || stopping_) return;
    guard_tick([this] { on_tick_timer(); });
  });
}

// A session's handler that throws closes that session alone (session.cpp); a tick
// that throws leaves the one world this server owns half stepped, and serving it on
// would send clients a state no replay reproduces. So the server says why and stops.
template <class Tick>
void Server::Impl::guard_tick(Tick&& tick) {
  try {
    tick();
  } catch (const std::exception& error) {
    log_with(spdlog::level::critical,
             {.tick = simulation_.current_tick() + 1, .reason = error.what()},
             "tick {} failed: {}; shutting down", simulation_.current_tick() + 1, error.what());
    update_stats([&](ServerStats& s) { s.tick_failure = error.what(); });
    begin_shutdown();
  }
}

void Server::Impl::on_tick_timer() {
  // At a fixed rate a tick is due when it runs: an input that arrives later is late.
  const phys::FrameResult frame = timestep_->frame([this](double) { run_one_tick(clock_.now()); });
  if (frame.dropped_steps > 0) {
    update_stats([&](ServerStats& s) { s.dropped_steps += frame.dropped_steps; });
    if (log_admits("dropped steps"))
      log_with(spdlog::level::warn, {.tick = simulation_.current_tick()},
               "fell behind: {} step(s) dropped after tick {}", frame.dropped_steps,
               simulation_.current_tick());
  }
  // The next wake-up is the previous one plus a period, never "now + period", so
  // the timer's own latency does not accumulate into drift.
  const auto period = timestep_->period();
  next_tick_due_ += period;
  const auto now = clock_.now();
  if (next_tick_due_ < now) {
    // Fell behind by whole periods (the driver already dropped that backlog): skip
    // them, keeping the phase, instead of firing once per missed period.
    const auto behind = now - next_tick_due_;
    next_tick_due_ += (behind / period + 1) * period;
  }
  arm_tick_timer();
}

void Server::Impl::schedule_lockstep() {
  // Inputs arrive many to a read; checking the gate in a posted handler, at most
  // one pending at a time, keeps stepping out of the read loop (see try_lockstep).
  if (lockstep_check_posted_ || stopping_) return;
  lockstep_check_posted_ = true;
  asio::post(io_, [this] {
    lockstep_check_posted_ = false;
    guard_tick([this] { try_lockstep(); });
  });
}

void Server::Impl::try_lockstep() {
  if (stopping_) return;
  const LockstepGate::Decision decision =
      gate_.decide(simulation_.all_inputs_present(), simulation_.any_input_present(), clock_.now());
  if (decision != LockstepGate::Decision::Wait) {
    // When this tick was due: realtime, its place on the tick clock; asap, when the
    // previous tick stepped (its inputs could have been there by then).
    std::optional<std::chrono::steady_clock::time_point> scheduled = last_lockstep_step_;
    if (config_.lockstep_pace == ServerConfig::Pace::Realtime) {
      const auto now = clock_.now();
      if (now < next_lockstep_due_) {
        lockstep_timer_.expires_at(next_lockstep_due_);
        lockstep_timer_.async_wait([this](std::error_code ec) {
          if (!ec) schedule_lockstep();
        });
        return;
      }
      if (last_lockstep_step_) scheduled = next_lockstep_due_;
      // Drift-free while on time; after a stall, no burst to catch up.
      next_lockstep_due_ = std::max(next_lockstep_due_ + tick_period_, now);
    }
    const TickResult result = run_one_tick(scheduled);
    last_lockstep_step_ = clock_.now();
    gate_.stepped();
    const bool timed_out = decision == LockstepGate::Decision::StepAfterTimeout;
    if (timed_out) {
      update_stats([&](ServerStats& s) {
        ++s.lockstep_timeouts;
        s.reused_inputs += result.held_over.size();
      });
      std::string missing;
      for (const ClientId client : result.held_over) {
        missing += (missing.empty() ? "" : ", ") + std::to_string(client);
      }
      log_with(spdlog::level::warn, {.tick = result.tick, .reason = "lockstep timeout"},
               "lockstep tick {} stepped after the {} ms timeout without input from client(s) {}",
               result.tick, config_.lockstep_timeout.count(), missing);
    }
    drop_stragglers(result, timed_out);
    // One tick per handler: when clients sent many ticks ahead, the write
    // completions of this tick's snapshots (queued before this post) run before the
    // next tick, so the sessions' snapshot queues drain instead of dropping.
    schedule_lockstep();
    return;
  }
  if (const auto deadline = gate_.deadline()) {
    lockstep_timer_.expires_at(*deadline);
    lockstep_timer_.async_wait([this](std::error_code ec) {
      if (!ec) schedule_lockstep();
    });
  } else {
    lockstep_timer_.cancel();
  }
}

TickResult Server::Impl::run_one_tick(
    std::optional<std::chrono::steady_clock::time_point> scheduled) {
  const auto started = std::chrono::steady_clock::now();
  input_timing_.stepped(simulation_.current_tick() + 1, scheduled);
  // Contact events cost the step nothing while nobody subscribes.
  simulation_.set_contact_events(feeds_.any_contact_subscriber());
  TickResult result = simulation_.step_tick();
  const BodyChanges changes = simulation_.take_changes();
  for (const phys::BodyId id : changes.added) feeds_.note_added(id.packed());
  for (const std::uint64_t id : changes.removed) feeds_.note_removed(id);
  TruthFrame frame = read_truth(simulation_.world(), result.tick, &previous_frame_);
  broadcast(frame);
  send_game_messages();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const double period = std::chrono::duration<double>(tick_period_).count();
  const bool overran = seconds > period;
  // At most a few lines a second (counted when suppressed): a scene too heavy for
  // its tick rate overruns every tick.
  if (overran && log_admits("tick overrun")) {
    log_with(spdlog::level::warn, {.tick = result.tick, .reason = "tick overrun"},
             "tick {} overran: {:.3f} ms for a {:.3f} ms period", result.tick, seconds * 1e3,
             period * 1e3);
  }
  const FeedStats& feed = feeds_.stats();
  std::size_t input_bytes = 0;
  for (const auto& [id, session] : sessions_) {
    if (const ClientInputs* inputs = simulation_.inputs_of(id))
      input_bytes += inputs->memory_bytes();
  }
  update_stats([&](ServerStats& s) {
    s.input_buffer_bytes = input_bytes;
    ++s.ticks_stepped;
    s.current_tick = result.tick;
    s.last_state_hash = frame.state_hash;
    s.last_tick_seconds = seconds;
    s.total_tick_seconds += seconds;
    if (seconds > s.max_tick_seconds) s.max_tick_seconds = seconds;
    const auto bound =
        std::lower_bound(kTickSecondsBounds.begin(), kTickSecondsBounds.end(), seconds);
    ++s.tick_seconds_buckets[static_cast<std::size_t>(bound - kTickSecondsBounds.begin())];
    if (overran) ++s.tick_overruns;
    s.last_tick_at = started;
    s.skipped_snapshots = feed.skipped;
    s.snapshots_sent = feed.snapshots;
    s.snapshot_records = feed.records;
    s.full_states = feed.full_states;
    s.view_updates = feed.views_updated;
    s.views = feeds_.view_count();
    s.max_view_error = feed.max_position_error;
    s.relay_ticks_held = relay_log_.ticks_held();
  });
  const std::uint64_t state_hash = frame.state_hash;
  previous_frame_ = std::move(frame);
  if (config_.on_tick) config_.on_tick(result.tick, state_hash);
  return result;
}

void Server::Impl::broadcast(const TruthFrame& frame) {
  std::vector<FeedOutput> outputs = feeds_.after_tick(
      frame, simulation_.world(),
      [this](FeedClient client) {
        const ClientInputs* inputs = simulation_.inputs_of(client);
        ClientFields fields;
        if (inputs != nullptr) {
          fields.last_applied_input_tick = inputs->last_applied_tick();
          fields.has_applied_input = inputs->has_applied();
        }
        return fields;
      },
      clock_.now());
  std::size_t peak = 0;
  for (FeedOutput& out : outputs) {
    const auto it = sessions_.find(out.client);
    if (it == sessions_.end()) continue;
    // Held by a copy: a session that turns out too slow closes, and leaves the map.
    const std::shared_ptr<Session> session = it->second;
    if (session->closing()) continue;
    if (const auto relay = relay_cursors_.find(out.client); relay != relay_cursors_.end()) {
      const std::uint32_t interval = feeds_.hash_interval(out.client);
      out.tail += relay_bytes(relay->second, out.tick, interval);
    }
    if (out.full) session->spend_full_state(out.shared->size() + out.tail.size());
    if (const auto margin = input_timing_.take_least_margin(out.client)) {
      // Appended to the client's own bytes: a second Snapshot message merges into one.
      physics::wire::Snapshot timing;
      timing.set_input_margin_us(margin->count());
      out.tail += timing.SerializeAsString();
    }
    session->send_snapshot(std::move(out.shared), std::move(out.tail));
    peak = std::max(peak, session->queued_snapshots());
  }
  update_stats(
      [&](ServerStats& s) { s.peak_queued_snapshots = std::max(s.peak_queued_snapshots, peak); });
}

// A player whose input was missing at lockstep_max_timeouts timed-out ticks in a row
// leaves the world now (so that the next tick no longer waits for it) and is told
// why; its session closes once the Error is written.
void Server::Impl::drop_stragglers(const TickResult& result, bool timed_out) {
  for (const ClientId id : stragglers_.after_step(result.held_over, timed_out)) {
    const auto it = sessions_.find(id);
    if (it == sessions_.end()) continue;
    const std::shared_ptr<Session> session = it->second;
    if (simulation_.leave(id)) {
      feeds_.leave(id);
      input_timing_.forget(id);
      publish_connection_counts();
    }
    stragglers_.forget(id);
    log_with(spdlog::level::warn,
             {.client = id,
              .address = session->peer(),
              .tick = simulation_.current_tick(),
              .reason = to_string(DropReason::LockstepStraggler)},
             "client {} '{}' ({}) dropped: no input at {} lockstep timeouts in a row", id,
             session->name(), session->peer(), stragglers_.limit());
    session->close_with_error(physics::wire::ERROR_LOCKSTEP_STRAGGLER,
                              "no input at " + std::to_string(stragglers_.limit()) +
                                  " consecutive lockstep timeouts (--lockstep-max-timeouts)",
                              DropReason::LockstepStraggler);
  }
}

std::string Server::Impl::relay_bytes(RelayCursor& cursor, std::uint64_t tick,
                                      std::uint32_t hash_interval) {
  physics::wire::Snapshot relay;
  if (cursor.resync || !relay_log_.holds_after(cursor.after_tick)) {
    // The world after `tick` replaces every tick the client has not been sent.
    const std::vector<std::uint8_t> bytes = simulation_.world().to_bytes();
    relay.set_world_state(bytes.data(), bytes.size());
    write_players(simulation_, *relay.mutable_players());
    cursor = {tick, relay_log_.next_change(), false, cursor.audience};
    update_stats([](ServerStats& s) { ++s.relay_resyncs; });
  } else {
    relay_log_.append(cursor.after_tick, tick, cursor.first_change, hash_interval, cursor.audience,
                      relay);
    // Their numbers are implied: consecutive, the last the snapshot's tick.
    wire::omit_relay_tick_numbers(relay);
    cursor.after_tick = tick;
  }
  return relay.SerializeAsString();
}

}  // namespace server
