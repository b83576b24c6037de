#include "relay_connection.h"

#include <algorithm>
#include <asio/write.hpp>
#include <utility>

namespace physics_testing {

namespace {

// The most one read takes from a sender.
constexpr std::size_t kReadBufferBytes = 16 * 1024;
// Under a bandwidth cap, one read takes about what the link sends in this long, so
// that a capped stream arrives as a trickle of small chunks, not in bursts of a whole
// buffer.
constexpr double kCappedReadSeconds = 0.001;
constexpr std::size_t kMinCappedReadBytes = 256;
// The most chunks one write gathers.
constexpr std::size_t kMaxChunksPerWrite = 64;

std::size_t read_size_for(const PathDirection& path) {
  if (path.bandwidth_bytes_per_second <= 0.0) return kReadBufferBytes;
  const double slice = path.bandwidth_bytes_per_second * kCappedReadSeconds;
  if (slice >= static_cast<double>(kReadBufferBytes)) return kReadBufferBytes;
  return std::max(kMinCappedReadBytes, static_cast<std::size_t>(slice));
}

// Direction 0 is to the server, 1 to the client; each has its own jitter and stall
// draws, all from the connection's seed.
DeliverySchedule direction_schedule(const PathConfig& path, int direction,
                                    std::chrono::steady_clock::time_point origin,
                                    std::uint64_t index) {
  PathRandom seeds(path.seed + index);
  for (int skip = 0; skip < 2 * direction; ++skip) seeds.next();
  const PathRandom jitter(seeds.next());
  const PathRandom stalls(seeds.next());
  const bool to_server = direction == 0;
  const bool stalls_apply = to_server ? path.stalls.to_server : path.stalls.to_client;
  return DeliverySchedule(to_server ? path.to_server : path.to_client,
                          StallTimeline(path.stalls, stalls_apply, origin, stalls), jitter);
}

bool same_stalls(const PathStalls& a, const PathStalls& b) {
  return a.duration == b.duration && a.per_second == b.per_second && a.every == b.every &&
         a.at == b.at && a.to_server == b.to_server && a.to_client == b.to_client;
}

void raise_to(std::atomic<std::uint64_t>& peak, std::uint64_t value) {
  std::uint64_t seen = peak.load(std::memory_order_relaxed);
  while (seen < value && !peak.compare_exchange_weak(seen, value, std::memory_order_relaxed)) {
  }
}

}  // namespace

RelayConnection::Direction::Direction(asio::ip::tcp::socket& from_socket,
                                      asio::ip::tcp::socket& to_socket,
                                      DeliverySchedule delivery_schedule,
                                      std::atomic<std::uint64_t>& delivered_counter)
    : from(from_socket),
      to(to_socket),
      schedule(std::move(delivery_schedule)),
      delivered(delivered_counter),
      timer(to_socket.get_executor()),
      read_buffer(kReadBufferBytes) {}

RelayConnection::RelayConnection(asio::ip::tcp::socket client, std::uint64_t index,
                                 const PathConfig& path, std::size_t max_held_bytes,
                                 std::shared_ptr<RelayCounters> counters)
    : client_(std::move(client)),
      server_(client_.get_executor()),
      max_held_bytes_(max_held_bytes),
      counters_(std::move(counters)),
      began_(Clock::now()),
      stalls_(path.stalls),
      to_server_(client_, server_, direction_schedule(path, 0, began_, index),
                 counters_->bytes_to_server),
      to_client_(server_, client_, direction_schedule(path, 1, began_, index),
                 counters_->bytes_to_client) {
  to_server_.read_size = read_size_for(path.to_server);
  to_client_.read_size = read_size_for(path.to_client);
}

void RelayConnection::start(const asio::ip::tcp::endpoint& target) {
  server_.async_connect(target, [self = shared_from_this()](const asio::error_code& error) {
    if (self->closed_) return;
    if (error) {
      self->close();
      return;
    }
    // The relay adds only the delay it is told to: no Nagle on its own writes.
    asio::error_code ignored;
    self->client_.set_option(asio::ip::tcp::no_delay(true), ignored);
    self->server_.set_option(asio::ip::tcp::no_delay(true), ignored);
    self->read(self->to_server_);
    self->read(self->to_client_);
  });
}

void RelayConnection::set_path(const PathConfig& path) {
  to_server_.schedule.set_path(path.to_server);
  to_client_.schedule.set_path(path.to_client);
  to_server_.read_size = read_size_for(path.to_server);
  to_client_.read_size = read_size_for(path.to_client);
  if (!same_stalls(stalls_, path.stalls)) {
    const Clock::time_point now = Clock::now();
    to_server_.schedule.stalls().reset(path.stalls, path.stalls.to_server, now);
    to_client_.schedule.stalls().reset(path.stalls, path.stalls.to_client, now);
    stalls_ = path.stalls;
  }
}

void RelayConnection::close() {
  if (closed_) return;
  closed_ = true;
  asio::error_code ignored;
  client_.close(ignored);
  server_.close(ignored);
  to_server_.timer.cancel();
  to_client_.timer.cancel();
}

void RelayConnection::read(Direction& direction) {
  if (closed_ || direction.reading || direction.read_ended) return;
  // Back-pressure: nothing more is read while the direction holds its most.
  if (direction.held_bytes >= max_held_bytes_) return;
  const std::size_t size = std::min(direction.read_size, max_held_bytes_ - direction.held_bytes);
  direction.reading = true;
  direction.from.async_read_some(
      asio::buffer(direction.read_buffer.data(), size),
      [self = shared_from_this(), &direction](const asio::error_code& error, std::size_t bytes) {
        self->on_read(direction, error, bytes);
      });
}

void RelayConnection::on_read(Direction& direction, const asio::error_code& error,
                              std::size_t bytes) {
  direction.reading = false;
  if (closed_) return;
  const Clock::time_point now = Clock::now();
  if (error == asio::error::eof) {
    // The FIN travels as the stream's last chunk: after every byte before it.
    direction.read_ended = true;
    const DeliverySchedule::Delivery delivery = direction.schedule.schedule(now, 0);
    counters_->stalls += delivery.stalls_begun;
    direction.held.push_back(Chunk{delivery.at, {}, true});
    deliver(direction);
    return;
  }
  if (error) {
    close();
    return;
  }
  const DeliverySchedule::Delivery delivery = direction.schedule.schedule(now, bytes);
  counters_->stalls += delivery.stalls_begun;
  const auto first = direction.read_buffer.begin();
  direction.held.push_back(
      Chunk{delivery.at, std::vector<std::uint8_t>(first, first + static_cast<long>(bytes))});
  direction.held_bytes += bytes;
  raise_to(counters_->held_bytes_peak, direction.held_bytes);
  deliver(direction);
  read(direction);
}

void RelayConnection::deliver(Direction& direction) {
  if (closed_ || direction.writing || direction.waiting || direction.held.empty()) return;
  const Clock::time_point now = Clock::now();
  const Chunk& first = direction.held.front();
  if (first.due > now) {
    direction.waiting = true;
    direction.timer.expires_at(first.due);
    direction.timer.async_wait([self = shared_from_this(), &direction](const asio::error_code&) {
      direction.waiting = false;
      self->deliver(direction);
    });
    return;
  }
  if (first.end_of_stream) {
    direction.held.pop_front();
    direction.finished = true;
    asio::error_code ignored;
    direction.to.shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
    // Both ways ended: both peers have sent all and we have delivered all.
    if (to_server_.finished && to_client_.finished) close();
    return;
  }
  std::vector<asio::const_buffer> buffers;
  for (const Chunk& chunk : direction.held) {
    if (chunk.due > now || chunk.end_of_stream || buffers.size() == kMaxChunksPerWrite) break;
    buffers.push_back(asio::buffer(chunk.bytes));
  }
  direction.writing = true;
  asio::async_write(direction.to, buffers,
                    [self = shared_from_this(), &direction, chunks = buffers.size()](
                        const asio::error_code& error, std::size_t bytes) {
                      self->on_written(direction, error, bytes, chunks);
                    });
}

void RelayConnection::on_written(Direction& direction, const asio::error_code& error,
                                 std::size_t bytes, std::size_t chunks) {
  direction.writing = false;
  if (closed_) return;
  if (error) {
    close();
    return;
  }
  for (std::size_t i = 0; i < chunks; ++i) direction.held.pop_front();
  direction.held_bytes -= bytes;
  direction.delivered += bytes;
  deliver(direction);
  read(direction);
}

}  // namespace physics_testing
