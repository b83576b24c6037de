#pragma once
// The parts of a Client that its two source files share: the socket and its
// io_context (client.cpp sends and waits; client_receive.cpp takes frames in), and
// what the client holds between snapshots.
#include <array>
#include <asio.hpp>
#include <chrono>
#include <cstdint>
#include <vector>

#include "client/client.h"
#include "wire/framing.h"
#include "wire/predictor.h"
#include "wire/reconstruction.h"

namespace client {

using Clock = std::chrono::steady_clock;

struct Client::Io {
  explicit Io(std::size_t max_message_bytes) : reader(max_message_bytes) {}
  asio::io_context context;
  asio::ip::tcp::socket socket{context};
  wire::FrameReader reader;
  std::array<std::uint8_t, 64 * 1024> buffer{};
  bool connect_done = false;
  std::error_code connect_error;

  // Runs handlers on this thread until `done()` or the deadline. False on timeout,
  // or when nothing is left that could make `done()` true.
  template <class Done>
  bool run_until(Clock::time_point deadline, Done done) {
    while (!done()) {
      if (context.stopped()) context.restart();
      if (context.run_one_until(deadline) == 0) {
        if (done()) return true;
        if (Clock::now() >= deadline || context.stopped()) return false;
      }
    }
    return true;
  }
};

// What the client holds between snapshots: the reconstruction the server mirrors,
// and the input fields, which the server sends only when they change.
struct Client::Held {
  wire::Reconstruction reconstruction;
  wire::Predictor predictor;
  wire::Quantum quantum;
  std::uint64_t last_applied_input_tick = 0;
  bool in_sync = true;  // as of the last snapshot that carried a view hash
  bool has_applied_input = false;
  // The kinematic bodies among those sent (Welcome, Snapshot.added), ascending id:
  // each snapshot's BodyState::motion comes from it.
  std::vector<std::uint64_t> kinematic_ids;
};

}  // namespace client
