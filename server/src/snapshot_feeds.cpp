#include "snapshot_feeds.h"

#include <algorithm>

#include "snapshot_encoder.h"

namespace server {

SnapshotFeeds::SnapshotFeeds(wire::Predictor predictor, std::uint64_t heartbeat_ticks,
                             bool lockstep)
    : predictor_(predictor),
      heartbeat_ticks_(std::max<std::uint64_t>(1, heartbeat_ticks)),
      lockstep_(lockstep) {}

// A view with an area of interest or a byte budget depends on the client's own
// body; only whole-world views without a budget can be shared.
bool SnapshotFeeds::can_share(const wire::ViewSettings& settings) {
  return settings.interest == wire::InterestKind::World && settings.byte_budget == 0;
}

std::uint64_t SnapshotFeeds::new_view(const wire::ViewSettings& settings, bool shareable) {
  const std::uint64_t id = next_view_++;
  ViewEntry entry;
  entry.view = std::make_unique<View>(settings, predictor_);
  entry.shareable = shareable;
  views_.emplace(id, std::move(entry));
  return id;
}

std::optional<std::uint64_t> SnapshotFeeds::shareable_view(
    const wire::ViewSettings& settings) const {
  if (!can_share(settings)) return std::nullopt;
  for (const auto& [id, entry] : views_) {
    if (entry.shareable && entry.view->settings() == settings) return id;
  }
  return std::nullopt;
}

void SnapshotFeeds::move_to(FeedClient client, Feed& feed, std::uint64_t view) {
  if (feed.view != 0) {
    auto old = views_.find(feed.view);
    if (old != views_.end()) {
      old->second.members.erase(client);
      if (old->second.members.empty()) views_.erase(old);
    }
  }
  feed.view = view;
  views_.at(view).members.insert(client);
}

void SnapshotFeeds::join(FeedClient client, const wire::ViewSettings& settings,
                         std::optional<std::uint64_t> own_body) {
  drop_feed(client);
  Feed feed;
  feed.settings = settings;
  feed.own = own_body;
  feed.unacked = AckWindow(settings.window, settings.window_adapts,
                           {tick_period_ * settings.snapshot_interval, max_window_});
  const std::optional<std::uint64_t> existing = shareable_view(settings);
  const std::uint64_t view = existing ? *existing : new_view(settings, can_share(settings));
  auto [it, inserted] = feeds_.emplace(client, std::move(feed));
  move_to(client, it->second, view);
}

void SnapshotFeeds::leave(FeedClient client) {
  drop_feed(client);
  contact_filters_.erase(client);
  sensor_subscribers_.erase(client);
}

void SnapshotFeeds::subscribe_contacts(FeedClient client, ContactFilter filter) {
  contact_filters_[client] = std::move(filter);
}

void SnapshotFeeds::subscribe_sensor_events(FeedClient client) {
  sensor_subscribers_.insert(client);
}

// Every subscriber that has joined files every sensor event.
void SnapshotFeeds::file_sensor_events(const TruthFrame& frame) {
  if (frame.sensor_events.empty()) return;
  for (const FeedClient client : sensor_subscribers_) {
    const auto it = feeds_.find(client);
    if (it == feeds_.end()) continue;
    Feed& feed = it->second;
    for (const phys::SensorEvent& event : frame.sensor_events) {
      if (feed.pending_sensor_events.size() < kMaxPendingSensorEvents) {
        feed.pending_sensor_events.push_back(event);
      } else {
        ++feed.dropped_sensor_events;
      }
    }
  }
}

// Every subscriber that has joined files the events it subscribed to.
void SnapshotFeeds::file_contact_events(const TruthFrame& frame) {
  if (frame.contact_events.empty()) return;
  for (const auto& [client, filter] : contact_filters_) {
    const auto it = feeds_.find(client);
    if (it == feeds_.end()) continue;
    Feed& feed = it->second;
    for (const phys::ContactEvent& event : frame.contact_events) {
      if (!filter.matches(event, feed.own)) continue;
      if (feed.pending_contacts.size() < kMaxPendingContactEvents) {
        feed.pending_contacts.push_back(event);
      } else {
        ++feed.dropped_contacts;
      }
    }
  }
}

void SnapshotFeeds::drop_feed(FeedClient client) {
  const auto it = feeds_.find(client);
  if (it == feeds_.end()) return;
  auto view = views_.find(it->second.view);
  if (view != views_.end()) {
    view->second.members.erase(client);
    if (view->second.members.empty()) views_.erase(view);
  }
  feeds_.erase(it);
}

void SnapshotFeeds::note_added(std::uint64_t id) {
  for (auto& [client, feed] : feeds_) feed.added.insert(id);
}

void SnapshotFeeds::note_removed(std::uint64_t id) {
  // A body added and removed before the client heard of it is never announced, so
  // each list holds at most the bodies the world or the client holds: other peers'
  // churn cannot grow it without bound.
  for (auto& [client, feed] : feeds_) {
    if (feed.added.erase(id) == 0) feed.removed.insert(id);
  }
}

void SnapshotFeeds::size_windows(std::chrono::nanoseconds tick_period, std::uint32_t max_window) {
  tick_period_ = tick_period;
  max_window_ = max_window;
}

AckResult SnapshotFeeds::ack(FeedClient client, std::uint64_t tick,
                             std::chrono::steady_clock::time_point now) {
  const auto it = feeds_.find(client);
  if (it == feeds_.end()) return AckResult::NeverSent;
  Feed& feed = it->second;
  if (!feed.last_sent || tick > *feed.last_sent) return AckResult::NeverSent;
  feed.unacked.acked(tick, now);
  return AckResult::Accepted;
}

FullStateResult SnapshotFeeds::request_full_state(FeedClient client) {
  const auto it = feeds_.find(client);
  if (it == feeds_.end()) return FullStateResult::AlreadyPending;
  Feed& feed = it->second;
  if (feed.needs_full) return FullStateResult::AlreadyPending;
  feed.needs_full = true;
  // A client that left a shared view (its window was full) goes back to it: the
  // full state it is sent is that view's mirror.
  if (!views_.at(feed.view).shareable) {
    if (const auto shared = shareable_view(feed.settings)) move_to(client, feed, *shared);
  }
  return FullStateResult::Accepted;
}

std::string SnapshotFeeds::tail_for(Feed& feed, const ClientFields& fields,
                                    const phys::World& world) {
  physics::wire::Snapshot own;
  // The input relay sends each added body's whole definition instead.
  if (feed.settings.encoding == physics::wire::ENCODING_INPUTS) {
    feed.added.clear();
    feed.removed.clear();
  }
  for (const std::uint64_t id : feed.added) {
    if (const auto body = world.body(phys::BodyId::from_packed(id))) {
      fill_body_shape(*body, world, *own.add_added());
    }
  }
  for (const std::uint64_t id : feed.removed) own.add_removed(id);
  feed.added.clear();
  feed.removed.clear();
  // Contact events go with the next snapshot sent, at most a snapshot's worth.
  const std::size_t events = std::min(feed.pending_contacts.size(), kMaxContactEventsPerSnapshot);
  for (std::size_t i = 0; i < events; ++i) {
    fill_contact_event(feed.pending_contacts[i], *own.add_contact_events());
  }
  feed.pending_contacts.erase(feed.pending_contacts.begin(),
                              feed.pending_contacts.begin() + static_cast<std::ptrdiff_t>(events));
  if (feed.dropped_contacts > 0) {
    own.set_contact_events_dropped(feed.dropped_contacts);
    feed.dropped_contacts = 0;
  }
  const std::size_t sensed =
      std::min(feed.pending_sensor_events.size(), kMaxSensorEventsPerSnapshot);
  for (std::size_t i = 0; i < sensed; ++i) {
    fill_sensor_event(feed.pending_sensor_events[i], *own.add_sensor_events());
  }
  feed.pending_sensor_events.erase(
      feed.pending_sensor_events.begin(),
      feed.pending_sensor_events.begin() + static_cast<std::ptrdiff_t>(sensed));
  if (feed.dropped_sensor_events > 0) {
    own.set_sensor_events_dropped(feed.dropped_sensor_events);
    feed.dropped_sensor_events = 0;
  }
  // The input fields go only when they changed: a client keeps the last it got.
  if (!feed.fields_ever_sent ||
      fields.last_applied_input_tick != feed.fields_sent.last_applied_input_tick ||
      fields.has_applied_input != feed.fields_sent.has_applied_input) {
    own.set_last_applied_input_tick(fields.last_applied_input_tick);
    own.set_has_applied_input(fields.has_applied_input);
    feed.fields_sent = fields;
    feed.fields_ever_sent = true;
  }
  return own.SerializeAsString();
}

std::vector<FeedOutput> SnapshotFeeds::run(const TruthFrame& frame, const phys::World& world,
                                           const std::map<FeedClient, ClientFields>& fields,
                                           std::chrono::steady_clock::time_point now) {
  file_contact_events(frame);
  file_sensor_events(frame);
  std::vector<FeedOutput> outputs;
  std::vector<std::uint64_t> ids;
  for (const auto& [id, entry] : views_) ids.push_back(id);
  const auto full_due = [&](const Feed& feed) { return feed.needs_full; };
  for (const std::uint64_t vid : ids) {
    auto found = views_.find(vid);
    if (found == views_.end()) continue;
    ViewEntry& entry = found->second;
    const wire::ViewSettings& settings = entry.view->settings();
    if (frame.tick % settings.snapshot_interval != 0) continue;
    std::vector<FeedClient> ready;
    std::vector<FeedClient> blocked;
    for (const FeedClient c : entry.members) {
      const Feed& feed = feeds_.at(c);
      (feed.unacked.open() ? ready : blocked).push_back(c);
    }
    stats_.skipped += blocked.size();
    if (ready.empty()) continue;  // the mirror waits with them: nobody falls out of step
    for (const FeedClient c : blocked) {
      // It holds the mirror as it is now, before this tick's records: it goes on
      // from a copy of it, in a view of its own.
      const std::uint64_t own_view = next_view_++;
      ViewEntry copy;
      copy.view = std::make_unique<View>(*entry.view);
      views_.emplace(own_view, std::move(copy));
      Feed& feed = feeds_.at(c);
      move_to(c, feed, own_view);
      ++stats_.detached;
    }
    ViewEntry& view_entry = views_.at(vid);
    View& view = *view_entry.view;
    const bool reset = std::all_of(view_entry.members.begin(), view_entry.members.end(),
                                   [&](FeedClient c) { return full_due(feeds_.at(c)); });
    std::optional<std::uint64_t> own;
    if (view_entry.members.size() == 1) own = feeds_.at(*view_entry.members.begin()).own;
    view.update(frame, own, reset);
    ++stats_.views_updated;
    stats_.max_position_error =
        std::max(stats_.max_position_error, view.last_stats().max_position_error);
    for (const FeedClient c : ready) {
      Feed& feed = feeds_.at(c);
      const bool full = full_due(feed);
      const auto f = fields.find(c);
      std::string tail = tail_for(feed, f != fields.end() ? f->second : ClientFields{}, world);
      const bool heartbeat = !feed.last_sent || frame.tick - *feed.last_sent >= heartbeat_ticks_;
      if (!(full || view.delta_has_news() || !tail.empty() || lockstep_ || heartbeat)) continue;
      FeedOutput out;
      out.client = c;
      out.tick = frame.tick;
      out.full = full;
      if (full && !reset) {
        out.shared = view.full_state();
        out.records = view.mirror().bodies().size();
      } else {
        out.shared = view.delta();
        out.records = view.last_stats().records;
      }
      out.tail = std::move(tail);
      if (full) {
        feed.needs_full = false;
        ++stats_.full_states;
      }
      feed.unacked.sent(frame.tick, now);
      feed.last_sent = frame.tick;
      ++stats_.snapshots;
      stats_.records += out.records;
      outputs.push_back(std::move(out));
    }
  }
  return outputs;
}

std::size_t SnapshotFeeds::unacknowledged(FeedClient client) const {
  const auto it = feeds_.find(client);
  return it == feeds_.end() ? 0 : it->second.unacked.unacknowledged();
}

std::uint32_t SnapshotFeeds::window(FeedClient client) const {
  const auto it = feeds_.find(client);
  return it == feeds_.end() ? 0 : it->second.unacked.window();
}

std::size_t SnapshotFeeds::view_members(FeedClient client) const {
  const auto it = feeds_.find(client);
  if (it == feeds_.end()) return 0;
  return views_.at(it->second.view).members.size();
}

const View* SnapshotFeeds::view_of(FeedClient client) const {
  const auto it = feeds_.find(client);
  if (it == feeds_.end()) return nullptr;
  return views_.at(it->second.view).view.get();
}

}  // namespace server
