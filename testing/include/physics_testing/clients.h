#pragma once
// Clients for a server under test, and waits with deadlines (never fixed sleeps)
// whose failures say what was seen.
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "client/client.h"
#include "physics_testing/outcome.h"

namespace physics_testing {

using Clients = std::vector<std::unique_ptr<client::Client>>;

// Connects `count` clients made from `base`, named "<base.name>-<k>", each on its
// own thread and all at once, so that a lockstep lobby (which welcomes nobody until
// every seat is taken) fills. Every one connected, or a message naming each that
// did not and why; the ones that did are then disconnected.
Expected<Clients> connect_clients(const client::ClientConfig& base, std::size_t count,
                                  std::chrono::milliseconds timeout = std::chrono::seconds(5));

// The first snapshot for which `done` is true, dropping the ones before it. On
// timeout or when the session ends: a message with `what`, how many snapshots were
// seen, the last tick, and the client's error.
Expected<client::Snapshot> wait_for_snapshot(
    client::Client& client, const std::function<bool(const client::Snapshot&)>& done,
    std::chrono::milliseconds timeout, std::string_view what = "the condition");

// Polls `done` (a cheap check such as a stats() read) until true or the deadline:
// for conditions that have no event to wait on.
Outcome eventually(const std::function<bool()>& done, std::chrono::milliseconds timeout,
                   std::string_view what = "the condition");

}  // namespace physics_testing
