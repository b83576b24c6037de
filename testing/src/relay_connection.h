#pragma once
// One connection through the link conditioner: the client's socket, the socket to the
// target, and a conditioned direction each way. Runs on the conditioner's io thread
// only; every handler holds the connection alive (shared_from_this).
#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/steady_timer.hpp>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "delivery_schedule.h"
#include "physics_testing/link_conditioner.h"

namespace physics_testing {

// What every connection adds to the conditioner's stats (LinkStats), from the io
// thread; read from any thread.
struct RelayCounters {
  std::atomic<std::uint64_t> connections{0};
  std::atomic<std::uint64_t> bytes_to_server{0};
  std::atomic<std::uint64_t> bytes_to_client{0};
  std::atomic<std::uint64_t> stalls{0};
  std::atomic<std::uint64_t> held_bytes_peak{0};
};

class RelayConnection : public std::enable_shared_from_this<RelayConnection> {
 public:
  // `index` counts connections from 0: its draws come from path.seed + index.
  RelayConnection(asio::ip::tcp::socket client, std::uint64_t index, const PathConfig& path,
                  std::size_t max_held_bytes, std::shared_ptr<RelayCounters> counters);

  // Connects to the target, then relays both ways.
  void start(const asio::ip::tcp::endpoint& target);
  void set_path(const PathConfig& path);
  // Closes both sockets at once (what is held is dropped).
  void close();

 private:
  using Clock = std::chrono::steady_clock;

  struct Chunk {
    Clock::time_point due;
    std::vector<std::uint8_t> bytes;
    bool end_of_stream = false;
  };

  struct Direction {
    Direction(asio::ip::tcp::socket& from, asio::ip::tcp::socket& to, DeliverySchedule schedule,
              std::atomic<std::uint64_t>& delivered);
    asio::ip::tcp::socket& from;
    asio::ip::tcp::socket& to;
    DeliverySchedule schedule;
    std::atomic<std::uint64_t>& delivered;
    asio::steady_timer timer;
    std::deque<Chunk> held;
    std::size_t held_bytes = 0;
    std::vector<std::uint8_t> read_buffer;
    std::size_t read_size = 0;  // at most read_buffer.size(): less under a bandwidth cap
    bool reading = false;
    bool read_ended = false;  // the sender's FIN is in `held`
    bool writing = false;
    bool waiting = false;
    bool finished = false;  // the FIN went on
  };

  void read(Direction& direction);
  void on_read(Direction& direction, const asio::error_code& error, std::size_t bytes);
  // Writes what is due, or waits for the first chunk's time.
  void deliver(Direction& direction);
  void on_written(Direction& direction, const asio::error_code& error, std::size_t bytes,
                  std::size_t chunks);

  asio::ip::tcp::socket client_;
  asio::ip::tcp::socket server_;
  std::size_t max_held_bytes_;
  std::shared_ptr<RelayCounters> counters_;
  Clock::time_point began_;
  PathStalls stalls_;
  Direction to_server_;
  Direction to_client_;
  bool closed_ = false;
};

}  // namespace physics_testing
