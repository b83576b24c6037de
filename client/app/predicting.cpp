#include "predicting.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "print.h"

namespace client_app {
namespace {

std::string format_prediction(const client::PredictingClient& player, bool json) {
  const client::PredictionCore& core = player.core();
  const client::PredictionStats& stats = core.stats();
  client::RenderBody own;
  for (const client::RenderBody& body : core.render().bodies) {
    if (body.body_id == core.own_body()) own = body;
  }
  if (json) {
    return fmt::format(
        "{{\"predicted_tick\":{},\"confirmed_tick\":{},\"own_body\":{},\"x\":{},\"y\":{},"
        "\"vx\":{},\"vy\":{},\"rollbacks\":{},\"resimulated_ticks\":{},\"desyncs\":{},"
        "\"resyncs\":{}}}",
        core.predicted_tick(), core.confirmed_tick(), core.own_body(), own.position.x,
        own.position.y, own.velocity.x, own.velocity.y, stats.rollbacks, stats.resimulated_ticks,
        stats.desyncs, stats.resyncs);
  }
  return fmt::format(
      "tick {} (confirmed {}) pos ({:.6f}, {:.6f}) vel ({:.6f}, {:.6f}) rollbacks {} "
      "resimulated {} desyncs {}",
      core.predicted_tick(), core.confirmed_tick(), own.position.x, own.position.y, own.velocity.x,
      own.velocity.y, stats.rollbacks, stats.resimulated_ticks, stats.desyncs);
}

}  // namespace

int run_predicting(const PredictingRun& run) {
  using namespace std::chrono_literals;
  client::PredictingClient player(run.config);
  if (!player.connect(run.connect_timeout)) {
    fmt::print(stderr, "physics-client: cannot join {}:{}: {}\n", run.config.client.host,
               run.config.client.port, player.error());
    return 1;
  }
  fmt::print(stderr, "{}\n", format_welcome(player.welcome(), false));
  if (run.json) fmt::print("{}\n", format_welcome(player.welcome(), true));
  client::GameMessageSender messages(run.messages);
  const client::GameMessageSender::Send send = [&](std::uint64_t tick, const std::string& payload) {
    return player.send_game_message(tick, payload);
  };
  const auto input = [&](std::uint64_t tick) {
    messages.before_input(send, tick, std::chrono::steady_clock::now());
    return run.pattern.at(tick);
  };
  const auto snapshot_timeout = std::max(
      2000ms, std::chrono::milliseconds(static_cast<long>(4000.0 / player.welcome().tick_rate)));
  std::uint64_t printed = 0;
  auto last_snapshot = std::chrono::steady_clock::now();
  while (run.ticks == 0 || printed < run.ticks) {
    const client::PollResult polled = player.poll(last_snapshot + snapshot_timeout, input);
    if (polled == client::PollResult::Ended ||
        std::chrono::steady_clock::now() >= last_snapshot + snapshot_timeout) {
      const std::string why = polled == client::PollResult::Ended
                                  ? player.error()
                                  : fmt::format("no snapshot for {} ms", snapshot_timeout.count());
      fmt::print(stderr, "physics-client: session ended after {} snapshots: {}\n", printed, why);
      return 3;
    }
    if (polled != client::PollResult::Snapshot) continue;
    last_snapshot = std::chrono::steady_clock::now();
    fmt::print("{}\n", format_prediction(player, run.json));
    for (const client::GameMessage& message : player.connection().take_game_messages()) {
      fmt::print("{}\n", format_game_message(message, run.json));
    }
    std::fflush(stdout);
    ++printed;
  }
  player.disconnect("physics-client done");
  return 0;
}

}  // namespace client_app
