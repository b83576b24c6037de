#pragma once
// Who gets which snapshot bytes after a tick. Each joined client has a feed: its
// view (shared with the clients whose settings and mirror equal its own), the
// snapshots it has not acknowledged yet, the bodies added and removed since it was
// last sent a snapshot, and its own input fields. Socket-free: the server hands the
// outputs to the sessions; tests drive it alone.
//
// Flow control: a client is sent a snapshot only while fewer than its window are
// unacknowledged. A client whose window is full skips ticks; if it shared a view,
// it leaves it with a copy of the mirror it holds, and its own view sends it what
// changed since, once the window opens.
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "ack_window.h"
#include "contact_subscription.h"
#include "physics/world.h"
#include "truth_frame.h"
#include "view.h"
#include "wire/view_settings.h"

namespace server {

using FeedClient = std::uint32_t;

struct ClientFields {
  std::uint64_t last_applied_input_tick = 0;
  bool has_applied_input = false;
};

// What one client is sent after a tick: the view's shared bytes, then its own.
struct FeedOutput {
  FeedClient client = 0;
  std::uint64_t tick = 0;
  std::shared_ptr<const std::string> shared;
  std::string tail;
  std::size_t records = 0;  // bodies in it
  bool full = false;
};

enum class AckResult { Accepted, NeverSent };
enum class FullStateResult { Accepted, AlreadyPending };

struct FeedStats {
  std::uint64_t views_updated = 0;  // view updates (each one encoding)
  std::uint64_t snapshots = 0;
  std::uint64_t records = 0;  // body records in the snapshots sent
  std::uint64_t skipped = 0;  // due snapshots not sent: the window was full
  std::uint64_t full_states = 0;
  std::uint64_t detached = 0;       // clients that left a shared view (window full)
  double max_position_error = 0.0;  // worst mirror-vs-world error over every update
};

class SnapshotFeeds {
 public:
  // `heartbeat_ticks`: a client that has been sent nothing for this many ticks gets
  // a snapshot of its header alone. `lockstep`: every client gets a snapshot on
  // every due tick (lockstep clients answer each one with an input).
  SnapshotFeeds(wire::Predictor predictor, std::uint64_t heartbeat_ticks, bool lockstep);

  void join(FeedClient client, const wire::ViewSettings& settings,
            std::optional<std::uint64_t> own_body);
  void leave(FeedClient client);
  bool has(FeedClient client) const { return feeds_.count(client) > 0; }

  // Contact events for `client` from its next snapshot on (it may subscribe before
  // it joins: a player waiting in the lobby). Held until leave().
  void subscribe_contacts(FeedClient client, ContactFilter filter);
  // Whether the world must produce contact events.
  bool any_contact_subscriber() const { return !contact_filters_.empty(); }
  // Every sensor's events for `client` from its next snapshot on (Hello.sensor_events),
  // until leave(). The world produces them always.
  void subscribe_sensor_events(FeedClient client);

  // Bodies added to and removed from the world, for every client's next snapshot.
  void note_added(std::uint64_t id);
  void note_removed(std::uint64_t id);

  // Windows of clients that left view.window unset grow with their round trip
  // (ack_window.h); off until called.
  void size_windows(std::chrono::nanoseconds tick_period, std::uint32_t max_window);

  AckResult ack(FeedClient client, std::uint64_t tick,
                std::chrono::steady_clock::time_point now = {});
  FullStateResult request_full_state(FeedClient client);

  // After a tick: the snapshots to send. `fields(client)` gives a client's input
  // fields; `world` gives the shapes of added bodies.
  template <class Fields>
  std::vector<FeedOutput> after_tick(const TruthFrame& frame, const phys::World& world,
                                     Fields&& fields,
                                     std::chrono::steady_clock::time_point now = {});

  // Snapshots sent to `client` and not acknowledged.
  std::size_t unacknowledged(FeedClient client) const;
  // The window `client` is held to now (its view's, or grown with its round trip).
  std::uint32_t window(FeedClient client) const;
  std::size_t view_count() const { return views_.size(); }
  std::size_t view_members(FeedClient client) const;
  const View* view_of(FeedClient client) const;
  // The client's view_hash_interval (0 for a client without a feed).
  std::uint32_t hash_interval(FeedClient client) const {
    const auto it = feeds_.find(client);
    return it == feeds_.end() ? 0 : it->second.settings.view_hash_interval;
  }
  const FeedStats& stats() const { return stats_; }

 private:
  struct Feed {
    wire::ViewSettings settings;
    std::optional<std::uint64_t> own;
    std::uint64_t view = 0;
    AckWindow unacked{1, false, {}};
    std::optional<std::uint64_t> last_sent;
    bool needs_full = true;
    std::set<std::uint64_t> added;
    std::set<std::uint64_t> removed;
    ClientFields fields_sent;
    bool fields_ever_sent = false;
    // Contact events not sent yet (they wait while no snapshot is due or the
    // window is full), oldest first, and those lost over kMaxPendingContactEvents.
    std::vector<phys::ContactEvent> pending_contacts;
    std::uint32_t dropped_contacts = 0;
    // The same for sensor events (kMaxPendingSensorEvents).
    std::vector<phys::SensorEvent> pending_sensor_events;
    std::uint32_t dropped_sensor_events = 0;
  };
  struct ViewEntry {
    std::unique_ptr<View> view;
    std::set<FeedClient> members;
    bool shareable = false;  // new clients with equal settings may join it
  };

  std::vector<FeedOutput> run(const TruthFrame& frame, const phys::World& world,
                              const std::map<FeedClient, ClientFields>& fields,
                              std::chrono::steady_clock::time_point now);
  std::uint64_t new_view(const wire::ViewSettings& settings, bool shareable);
  std::optional<std::uint64_t> shareable_view(const wire::ViewSettings& settings) const;
  static bool can_share(const wire::ViewSettings& settings);
  void move_to(FeedClient client, Feed& feed, std::uint64_t view);
  void drop_feed(FeedClient client);
  void file_contact_events(const TruthFrame& frame);
  void file_sensor_events(const TruthFrame& frame);
  std::string tail_for(Feed& feed, const ClientFields& fields, const phys::World& world);

  wire::Predictor predictor_;
  std::uint64_t heartbeat_ticks_;
  std::chrono::nanoseconds tick_period_{0};  // 0: windows do not grow
  std::uint32_t max_window_ = 0;
  bool lockstep_;
  std::map<FeedClient, Feed> feeds_;
  std::map<FeedClient, ContactFilter> contact_filters_;
  std::set<FeedClient> sensor_subscribers_;
  std::map<std::uint64_t, ViewEntry> views_;
  std::uint64_t next_view_ = 1;
  FeedStats stats_;
};

template <class Fields>
std::vector<FeedOutput> SnapshotFeeds::after_tick(const TruthFrame& frame, const phys::World& world,
                                                  Fields&& fields,
                                                  std::chrono::steady_clock::time_point now) {
  std::map<FeedClient, ClientFields> all;
  for (const auto& [client, feed] : feeds_) all.emplace(client, fields(client));
  return run(frame, world, all, now);
}

}  // namespace server
