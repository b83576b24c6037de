#pragma once
// A link conditioner: a TCP relay on loopback that delivers each direction's bytes
// late, as a real path would. One-way latency per direction, jitter that keeps TCP's
// order, a bandwidth cap, and stalls as TCP shows a lost segment (the stream held for
// about a retransmission time), at a given rate or at scripted times. Seeded, so a run
// can be repeated. It models what an application sees of a path through TCP, not
// TCP's own congestion control (docs/NETSIM.md).
//
// The relay runs its own thread; every call here is safe from any thread.
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace physics_testing {

// One direction of the path.
struct PathDirection {
  // Every byte arrives this long after it was sent, at least.
  std::chrono::microseconds latency{0};
  // Plus a delay drawn uniformly from [0, jitter] per chunk read, but never before
  // the chunk sent ahead of it (TCP delivers in order).
  std::chrono::microseconds jitter{0};
  // Bytes per second on the wire (0: no cap): a chunk of n bytes occupies the link
  // for n / bandwidth seconds after the one before it.
  double bandwidth_bytes_per_second = 0.0;
};

// Stalls: the direction delivers nothing for `duration`, then everything held at
// once, as a TCP receiver sees a segment lost and resent after the RTO.
struct PathStalls {
  std::chrono::milliseconds duration{0};  // 0: no stalls
  // Random stalls, Poisson with this mean rate per second of connection time.
  double per_second = 0.0;
  // Periodic stalls: one every `every` (from the connection's start), 0: none.
  std::chrono::milliseconds every{0};
  // Scripted stalls: times from the connection's start.
  std::vector<std::chrono::milliseconds> at;
  // Which directions stall: to the server (client's sends), to the client.
  bool to_server = true;
  bool to_client = true;
};

struct PathConfig {
  PathDirection to_server;  // client -> server
  PathDirection to_client;  // server -> client
  PathStalls stalls;
  std::uint64_t seed = 1;  // jitter and random stalls; each connection k uses seed + k
};

// A path with `one_way` latency and `jitter` both ways.
PathConfig symmetric_path(std::chrono::microseconds one_way,
                          std::chrono::microseconds jitter = std::chrono::microseconds{0});

struct LinkConditionerConfig {
  std::string listen_host = "127.0.0.1";  // loopback only (127.0.0.0/8 or ::1)
  std::uint16_t listen_port = 0;          // 0: any free port (port() tells which)
  std::string target_host = "127.0.0.1";  // loopback only
  std::uint16_t target_port = 0;
  PathConfig path;
  // Bytes held in one direction before the relay stops reading from its sender, so a
  // fast sender meets back-pressure instead of growing the relay's memory.
  std::size_t max_held_bytes = 4u << 20;
};

// A relay from a free loopback port to a server on loopback `port`, over `path`.
LinkConditionerConfig relay_to(std::uint16_t port, PathConfig path);

struct LinkStats {
  std::uint64_t connections = 0;      // accepted so far
  std::uint64_t bytes_to_server = 0;  // delivered
  std::uint64_t bytes_to_client = 0;
  std::uint64_t stalls = 0;           // begun, both directions
  std::uint64_t held_bytes_peak = 0;  // the most bytes held at once in one direction
};

class LinkConditioner {
 public:
  // Listens at once; throws std::invalid_argument for a non-loopback address or bad
  // settings (negative, NaN), std::runtime_error when it cannot listen.
  explicit LinkConditioner(LinkConditionerConfig config);
  // Closes every connection and stops the thread.
  ~LinkConditioner();
  LinkConditioner(const LinkConditioner&) = delete;
  LinkConditioner& operator=(const LinkConditioner&) = delete;

  std::uint16_t port() const;
  // Changes the path of every connection, open and future, from now on (bytes
  // already scheduled keep their times; order is kept): a round trip that jumps
  // mid-match.
  void set_path(const PathConfig& path);
  LinkStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace physics_testing
