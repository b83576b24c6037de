#pragma once
// physics-soak's client fleet: one slot per client, each joining, sending scripted
// inputs and reading snapshots; a seeded RNG makes slots leave (and join again
// later) or stop reading for a while. What the clients received is kept in a Tally
// for the replay check and the report.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "client/client.h"
#include "server/server.h"
#include "soak_options.h"

namespace soak {

using Clock = std::chrono::steady_clock;

// One client slot. The RNG decides when it leaves and when it stops reading.
struct Slot {
  std::unique_ptr<client::Client> client;
  std::size_t index = 0;
  std::uint64_t sent_through = 0;  // the last tick an input was sent for
  Clock::time_point rejoin_at{};   // vacant: when to join again
  Clock::time_point reading_at{};  // stalled: when to read again
  bool joined() const { return client != nullptr; }
};

struct Tally {
  // Every state hash a client received, by tick; a tick where two clients were
  // sent different hashes is a desync already.
  std::map<std::uint64_t, std::uint64_t> hashes;
  std::uint64_t hash_samples = 0;
  std::uint64_t cross_client_conflicts = 0;
  std::uint64_t snapshots = 0;
  std::uint64_t joins = 0;
  std::uint64_t leaves = 0;         // the tool's own Byes
  std::uint64_t stalls = 0;         // periods of not reading that the tool began
  std::uint64_t lost_sessions = 0;  // sessions that ended without the tool leaving
  std::uint64_t join_failures = 0;
  std::uint64_t join_refused_no_spawn = 0;
  std::uint64_t view_desyncs = 0;  // ClientStats::desyncs over every session
  std::uint64_t global_tick = 0;   // the newest tick any client was sent
};

class ClientFleet {
 public:
  ClientFleet(const Options& options, server::Server& server);

  Tally& tally() { return tally_; }

  bool join(Slot& slot);
  void leave(Slot& slot, Clock::time_point now);
  void join_all();

  // One scripted event: a slot picked by the RNG leaves, or stops reading for 0.5
  // to 3 s (well inside the idle timeout: it must not be dropped for it).
  void scripted_event(Clock::time_point now);

  // Everything each slot does in one pass: join when due, read when not stalled,
  // send the inputs up to a few ticks ahead of the newest tick seen.
  void pass(Clock::time_point now);

  // The last read of every joined slot, before the server stops.
  void finish();

  // The slots holding a session (at the stop: the sessions the server shuts down).
  std::uint64_t joined() const;

  // After the server stopped: the clients go (their sessions ended as ShuttingDown).
  void close_all();

 private:
  void read(client::Client& player);
  void take(const client::Snapshot& snapshot);
  void send_inputs(Slot& slot);
  void lost(Slot& slot, Clock::time_point now);

  const Options& options_;
  server::Server& server_;
  std::mt19937_64 rng_;  // its output is fixed by the standard; no distributions used
  std::vector<Slot> slots_;
  Tally tally_;
};

}  // namespace soak
