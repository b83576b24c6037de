#include "physics_testing/clients.h"

#include <string>
#include <thread>

namespace physics_testing {

Expected<Clients> connect_clients(const client::ClientConfig& base, std::size_t count,
                                  std::chrono::milliseconds timeout) {
  Clients clients;
  for (std::size_t k = 0; k < count; ++k) {
    client::ClientConfig config = base;
    config.name = base.name + "-" + std::to_string(k);
    clients.push_back(std::make_unique<client::Client>(std::move(config)));
  }
  // One Client is used by one thread at a time: each connects on its own.
  std::vector<char> connected(count, 0);
  {
    std::vector<std::jthread> threads;
    for (std::size_t k = 0; k < count; ++k) {
      threads.emplace_back(
          [&, k] { connected[k] = clients[k]->connect(timeout) ? char{1} : char{0}; });
    }
  }
  std::string failures;
  for (std::size_t k = 0; k < count; ++k) {
    if (connected[k] != 0) continue;
    if (!failures.empty()) failures += "; ";
    failures += "client " + std::to_string(k) + ": " + clients[k]->last_error().to_string();
  }
  if (!failures.empty()) {
    for (auto& c : clients) c->disconnect("a sibling failed to connect");
    return Expected<Clients>::failure("not every client connected (" + std::to_string(count) +
                                      " asked for): " + failures);
  }
  return clients;
}

Expected<client::Snapshot> wait_for_snapshot(
    client::Client& client, const std::function<bool(const client::Snapshot&)>& done,
    std::chrono::milliseconds timeout, std::string_view what) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::size_t seen = 0;
  std::optional<std::uint64_t> last_tick;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    std::optional<client::Snapshot> snapshot =
        client.next_snapshot(left.count() > 0 ? left : std::chrono::milliseconds(0));
    if (!snapshot) break;
    ++seen;
    last_tick = snapshot->tick;
    if (done(*snapshot)) return std::move(*snapshot);
  }
  std::string message = "no snapshot with " + std::string(what) + " within " +
                        std::to_string(timeout.count()) + " ms: " + std::to_string(seen) + " seen";
  if (last_tick) message += ", the last at tick " + std::to_string(*last_tick);
  if (client.state() != client::ConnectionState::Connected) {
    message += "; client: " + client.last_error().to_string();
  }
  return Expected<client::Snapshot>::failure(std::move(message));
}

Outcome eventually(const std::function<bool()>& done, std::chrono::milliseconds timeout,
                   std::string_view what) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() >= deadline) {
      return Outcome::failure(std::string(what) + " did not hold within " +
                              std::to_string(timeout.count()) + " ms");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return Outcome::success();
}

}  // namespace physics_testing
