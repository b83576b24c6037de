// physics-client: connects to a physics-server, sends accelerations for its own
// body and prints one line per snapshot; --bots N runs N clients as a load test.
// Exit codes: 0 done, 1 could not connect or refused, 2 bad flags (as physics-server
// and physics-sim), 3 the session ended early (the server dropped us or closed).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "client/client.h"
#include "client/game_message_plan.h"
#include "client/game_rules_loader.h"
#include "client/input_pacer.h"
#include "client/load.h"
#include "pattern.h"
#include "predicting.h"
#include "print.h"

namespace {

using namespace std::chrono_literals;

constexpr int kExitConnect = 1;
constexpr int kExitUsage = 2;
constexpr int kExitLost = 3;

struct Options {
  client::ClientConfig client;
  client::PacerConfig pacer;
  std::vector<double> accel;
  std::uint64_t ticks = 0;  // 0: until the server ends the session
  bool json = false;
  int bots = 0;
  bool predict = false;
  client::PredictionConfig prediction;
  double duration_seconds = 5.0;
  int connect_timeout_ms = 5000;
  int input_change_ms = 0;
  client::GameMessagePlan messages;
  std::string rules_file;  // --rules: the game's rules, run in the prediction
  std::string scene_file;  // --scene: the scene they are made for
  client::RulesMaker make_rules;
};

int run_single(const Options& options) {
  client::Client connection(options.client);
  if (!connection.connect(std::chrono::milliseconds(options.connect_timeout_ms))) {
    fmt::print(stderr, "physics-client: cannot join {}:{}: {}\n", options.client.host,
               options.client.port, connection.last_error().to_string());
    return kExitConnect;
  }
  const client::Welcome& welcome = connection.welcome();
  fmt::print(stderr, "{}\n", client_app::format_welcome(welcome, false));
  if (options.json) fmt::print("{}\n", client_app::format_welcome(welcome, true));

  client_app::AccelerationPattern pattern;
  if (options.accel.size() == 2)
    pattern.constant = client::Vec2{options.accel[0], options.accel[1]};

  // Inputs go out on the client's own clock, ahead of the server by the input delay
  // (docs/PROTOCOL.md 3.4): in lockstep the server then keeps its tick rate at any
  // round trip. The acceleration of a tick depends on the tick alone.
  const bool watching = welcome.spectator;  // a spectator has no body to steer
  client::InputPacer pacer(connection, options.pacer);
  client::GameMessageSender messages(options.messages);
  const auto input = [&](std::uint64_t tick) {
    messages.before_input(connection, tick, std::chrono::steady_clock::now());
    return pattern.at(tick);
  };
  // Without a snapshot for this long the server is presumed gone.
  const auto snapshot_timeout =
      std::max(2000ms, std::chrono::milliseconds(static_cast<long>(4000.0 / welcome.tick_rate)));
  std::uint64_t printed = 0;
  while (options.ticks == 0 || printed < options.ticks) {
    auto snapshot = watching
                        ? connection.next_snapshot(snapshot_timeout)
                        : pacer.poll(std::chrono::steady_clock::now() + snapshot_timeout, input);
    if (!snapshot) {
      const std::string why = connection.state() == client::ConnectionState::Connected
                                  ? fmt::format("no snapshot for {} ms", snapshot_timeout.count())
                                  : connection.last_error().to_string();
      fmt::print(stderr, "physics-client: session ended after {} snapshots: {}\n", printed, why);
      return kExitLost;
    }
    fmt::print("{}\n", client_app::format_snapshot(*snapshot, options.json,
                                                   options.client.view.state_hash));
    for (const client::ContactEvent& event : snapshot->contact_events) {
      fmt::print("{}\n", client_app::format_contact_event(event, options.json));
    }
    for (const client::GameMessage& message : connection.take_game_messages()) {
      fmt::print("{}\n", client_app::format_game_message(message, options.json));
    }
    if (snapshot->contact_events_dropped > 0) {
      fmt::print(stderr, "physics-client: {} contact events lost over the server's limit\n",
                 snapshot->contact_events_dropped);
    }
    std::fflush(stdout);
    ++printed;
    while (auto error = connection.next_error(0ms)) {
      fmt::print(stderr, "physics-client: server error {}: {}\n", client::to_string(error->code),
                 error->message);
    }
  }
  connection.disconnect("physics-client done");
  return 0;
}

int run_bots(const Options& options) {
  client::LoadConfig load;
  load.client = options.client;
  load.bots = options.bots;
  load.duration = std::chrono::milliseconds(static_cast<long>(options.duration_seconds * 1000.0));
  load.connect_timeout = std::chrono::milliseconds(options.connect_timeout_ms);
  load.pacer = options.pacer;
  load.input_change_interval = std::chrono::milliseconds(options.input_change_ms);
  load.predict = options.predict;
  load.prediction = options.prediction;
  load.messages = options.messages;
  load.make_rules = options.make_rules;
  const client::LoadReport report = client::run_load(load);
  fmt::print("{}\n", client_app::format_load_report(report, options.json));
  if (report.bots_connected == 0) {
    fmt::print(stderr, "physics-client: no bot could join\n");
    return kExitConnect;
  }
  return report.bots_connected == report.bots_requested ? 0 : kExitLost;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"physics-client: joins a physics-server, steers its own body, prints snapshots"};
  Options options;
  app.add_option("--host", options.client.host, "Server address")->capture_default_str();
  int port = options.client.port;
  app.add_option("--port", port, "Server port")->capture_default_str()->check(CLI::Range(1, 65535));
  std::int64_t seat = -1;
  app.add_option("--seat", seat,
                 "The seat to play in (Hello.seat, 0 to the server's seats - 1): with "
                 "--lockstep-players it decides the body, whatever order clients connect in; "
                 "default: the lowest free seat")
      ->check(CLI::Range(std::int64_t{0}, std::int64_t{4294967295}));
  app.add_option("--token", options.client.token, "Access token, when the server wants one");
  app.add_option("--name", options.client.name, "Name shown in the server's log")
      ->capture_default_str();
  app.add_option("--accel", options.accel,
                 "Constant acceleration X,Y in m/s^2 (default: a circle of 5 m/s^2 every 120 "
                 "ticks)")
      ->delimiter(',')
      ->expected(2);
  app.add_option("--ticks", options.ticks, "Snapshots to print before leaving (0: no limit)")
      ->capture_default_str();
  app.add_flag("--json", options.json, "Print JSON lines instead of text");
  app.add_option("--bots", options.bots,
                 "Load mode: run this many clients, each sending an input every tick, and "
                 "report latency and bandwidth")
      ->check(CLI::Range(1, 4096));
  app.add_flag("--predict", options.predict,
               "Run the world here and predict (the input relay; client/predicting_client.h): "
               "the own input shows at once, corrections roll back and are smoothed");
  app.add_option("--max-rollback", options.prediction.max_rollback,
                 "With --predict: ticks the prediction may run past the server's confirmed "
                 "tick, the deepest rollback")
      ->capture_default_str()
      ->check(CLI::Range(0, 600));
  app.add_option("--input-change-ms", options.input_change_ms,
                 "Load mode: each bot holds its input this long before it changes (an input "
                 "is still sent every tick; 0: a new one every tick)")
      ->capture_default_str()
      ->check(CLI::Range(0, 600000))
      ->needs("--bots");
  app.add_option("--duration", options.duration_seconds, "Load mode: seconds to measure")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  app.add_option("--connect-timeout-ms", options.connect_timeout_ms,
                 "How long to wait for the connection and the Welcome")
      ->check(CLI::Range(1, 600000))
      ->capture_default_str();
  std::int64_t input_delay = -1;
  app.add_option("--input-delay", input_delay,
                 "Send each input this many ticks ahead of the server's tick (default: chosen "
                 "from the round trip and adapted to the margins the server reports)")
      ->check(CLI::Range(std::int64_t{0}, std::int64_t{1000}));
  std::string schedule = "clock";
  app.add_option("--input-schedule", schedule,
                 "When inputs are sent: clock (ahead by the input delay, on the client's "
                 "clock) or after-snapshot (the input for T+1 once the snapshot of T arrived: "
                 "a lockstep server then waits a round trip a tick)")
      ->capture_default_str()
      ->check(CLI::IsMember({"clock", "after-snapshot"}));
  // The view (docs/PROTOCOL.md, section 5.1); the server checks every range.
  std::string encoding = "predicted";
  app.add_option("--encoding", encoding,
                 "How snapshots describe the bodies: predicted (quantised, only what left the "
                 "prediction), exact (exact doubles, only what changed), full (every body)")
      ->capture_default_str()
      ->check(CLI::IsMember({"predicted", "exact", "full"}));
  app.add_option("--position-precision", options.client.view.position_precision,
                 "Metres per quantum of a position (server default 0.001)");
  app.add_option("--velocity-precision", options.client.view.velocity_precision,
                 "m/s per quantum of a velocity (server default 0.001)");
  app.add_option("--position-tolerance", options.client.view.position_tolerance,
                 "Resend a body once its position is off by more (server default 0.01 m)");
  app.add_option("--velocity-tolerance", options.client.view.velocity_tolerance,
                 "Resend a body once its velocity is off by more (server default 0.1 m/s)");
  app.add_option("--snapshot-interval", options.client.view.snapshot_interval,
                 "A snapshot every k-th tick (server default 1)");
  app.add_option("--window", options.client.view.window,
                 "Snapshots sent and not yet acknowledged, at most (server default 12)");
  app.add_option("--interest-radius", options.client.view.interest_radius,
                 "Only bodies within this many metres of the own body");
  app.add_option("--byte-budget", options.client.view.byte_budget,
                 "Bytes of body records per snapshot, about (0: none)");
  app.add_flag("--state-hash", options.client.view.state_hash,
               "Ask for the world's state hash in every snapshot");
  app.add_flag("--spectate", options.client.spectate,
               "Watch without a body (sends no inputs; the server's --max-spectators applies)");
  app.add_option("--record", options.client.record_path,
                 "Write every message received to FILE, a client recording (docs/REPLAY.md)")
      ->excludes("--bots");
  bool contacts = false;
  std::vector<std::uint64_t> contact_bodies;
  app.add_flag("--contacts", contacts,
               "Print contact events: a player's own body's, a spectator's of every body");
  app.add_option("--contact-bodies", contact_bodies,
                 "Spectators: print the contact events of these body ids only (at most 64)");
  auto* rules = app.add_option("--rules", options.rules_file,
                               "With --predict: run this game's rules library (the one "
                               "physics-server --rules runs) in the prediction, so that the own "
                               "game messages show at once (docs/CLIENT.md)")
                    ->check(CLI::ExistingFile);
  app.add_option("--scene", options.scene_file,
                 "With --rules: the game's scene file the rules are made for (default: the "
                 "built-in scene)")
      ->check(CLI::ExistingFile)
      ->needs(rules);
  auto* game_message =
      app.add_option("--game-message", options.messages.payloads,
                     "Send this game message (docs/PROTOCOL.md 3.9) just before the first input; "
                     "repeat for up to 4, sent together in order. Received game messages are "
                     "printed, the payload as text when it is UTF-8, else as base64")
          ->excludes("--spectate");
  int message_every_ms = 0;
  app.add_option("--message-every-ms", message_every_ms,
                 "Send the --game-message payloads again every N ms, before the input of the "
                 "tick then due (default: once)")
      ->check(CLI::Range(1, 3600000))
      ->needs(game_message);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? 0 : kExitUsage;
  }
  options.client.port = static_cast<std::uint16_t>(port);
  if (input_delay >= 0) options.pacer.clock.fixed_delay = static_cast<std::uint32_t>(input_delay);
  options.pacer.schedule = schedule == "after-snapshot" ? client::InputSchedule::AfterSnapshot
                                                        : client::InputSchedule::Clock;
  if (seat >= 0) options.client.seat = static_cast<std::uint32_t>(seat);
  if (contacts || !contact_bodies.empty()) {
    client::ContactSubscription subscription;
    subscription.all = options.client.spectate && contact_bodies.empty();
    subscription.body_ids = contact_bodies;
    options.client.contacts = subscription;
  }
  options.client.view.encoding = encoding == "exact"  ? client::Encoding::Exact
                                 : encoding == "full" ? client::Encoding::Full
                                                      : client::Encoding::Predicted;

  options.messages.every = std::chrono::milliseconds(message_every_ms);
  if (const std::string problem = client::check_game_message_plan(options.messages);
      !problem.empty()) {
    fmt::print(stderr, "physics-client: --game-message: {}\n", problem);
    return kExitUsage;
  }
  for (const double value : options.accel) {
    if (!std::isfinite(value)) {
      fmt::print(stderr, "physics-client: --accel must be finite numbers\n");
      return kExitUsage;
    }
  }
  if (!options.rules_file.empty()) {
    if (!options.predict) {
      fmt::print(stderr,
                 "physics-client: --rules runs the rules in the prediction: add --predict\n");
      return kExitUsage;
    }
    std::string why;
    options.make_rules = client::load_game_rules(options.rules_file, options.scene_file, &why);
    if (!options.make_rules) {
      fmt::print(stderr, "physics-client: --rules: {}\n", why);
      return kExitUsage;
    }
  }
  if (options.predict && options.bots == 0) {
    client_app::PredictingRun run;
    run.config.client = options.client;
    run.config.pacer = options.pacer;
    run.config.prediction = options.prediction;
    if (options.make_rules) run.config.rules = options.make_rules();
    if (options.accel.size() == 2)
      run.pattern.constant = client::Vec2{options.accel[0], options.accel[1]};
    run.messages = options.messages;
    run.ticks = options.ticks;
    run.json = options.json;
    run.connect_timeout = std::chrono::milliseconds(options.connect_timeout_ms);
    return client_app::run_predicting(run);
  }
  return options.bots > 0 ? run_bots(options) : run_single(options);
}
