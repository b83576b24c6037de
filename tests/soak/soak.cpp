// physics-soak: a long networked run checked end to end. An in-process server on a
// scene (moving-1000 by default) with 64 client slots, at a fixed rate or in
// lockstep; a seeded RNG picks, every quarter second, one slot to leave (and join
// again later) or to stop reading for a while. The server records the run; at the
// end the recording is replayed in-process and every state hash any client received
// must equal the replay's for that tick. It also reports every session end by
// reason, the process's resident memory after warm-up, the server's own structure
// sizes and its tick time against the tick budget.
//
// Exit: 0 all checks passed, 1 a desync or an unexplained drop, 2 bad flags or files.
#include <fmt/format.h>
#include <malloc.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "client/client.h"
#include "replayer.h"
#include "scene/scene.h"
#include "server/server.h"

namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

struct Options {
  std::string scene_file = "scenes/moving-1000.textproto";
  bool lockstep = false;
  double duration = 60.0;
  double warmup = 10.0;
  int clients = 64;
  std::uint64_t seed = 1;
  std::string record_path;  // empty: a temporary file, removed at the end
  std::string csv_path;
  client::Encoding encoding = client::Encoding::Predicted;
};

// The process's resident set (bytes), from /proc/self/statm: server and clients.
std::uint64_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t size = 0;
  std::uint64_t resident = 0;
  statm >> size >> resident;
  return resident * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

// One client slot. The RNG decides when it leaves and when it stops reading.
struct Slot {
  std::unique_ptr<client::Client> client;
  std::size_t index = 0;
  std::uint64_t sent_through = 0;  // the last tick an input was sent for
  Clock::time_point rejoin_at{};   // vacant: when to join again
  Clock::time_point reading_at{};  // stalled: when to read again
  bool joined() const { return client != nullptr; }
};

// Slot k's acceleration at tick t: changes every 5 ticks, small against any
// scene's max_acceleration.
std::pair<double, double> scripted_input(std::size_t k, std::uint64_t t) {
  const double phase = static_cast<double>(t / 5) * 0.7 + static_cast<double>(k) * 1.3;
  return {3.0 * std::cos(phase), 3.0 * std::sin(phase)};
}

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

class Soak {
 public:
  Soak(const Options& options, server::Server& server)
      : options_(options), server_(server), rng_(options.seed) {
    slots_.resize(static_cast<std::size_t>(options.clients));
    for (std::size_t k = 0; k < slots_.size(); ++k) slots_[k].index = k;
  }

  Tally& tally() { return tally_; }

  bool join(Slot& slot) {
    client::ClientConfig config;
    config.port = server_.port();
    config.name = fmt::format("soak-{}", slot.index);
    config.view.state_hash = true;
    config.view.encoding = options_.encoding;
    auto player = std::make_unique<client::Client>(config);
    if (!player->connect(5s)) {
      const client::ClientError& error = player->last_error();
      if (error.server && error.server->code == client::ErrorCode::NoSpawn) {
        ++tally_.join_refused_no_spawn;
      } else {
        ++tally_.join_failures;
        fmt::print(stderr, "physics-soak: slot {} could not join: {}\n", slot.index,
                   error.to_string());
      }
      slot.rejoin_at = Clock::now() + 1s;
      return false;
    }
    slot.sent_through = player->welcome().current_tick;
    slot.reading_at = Clock::now();
    slot.client = std::move(player);
    ++tally_.joins;
    return true;
  }

  void leave(Slot& slot, Clock::time_point now) {
    tally_.view_desyncs += slot.client->stats().desyncs;
    slot.client->disconnect("soak: leaving");
    slot.client.reset();
    ++tally_.leaves;
    slot.rejoin_at = now + std::chrono::milliseconds(500 + rng_() % 1500);
  }

  void join_all() {
    for (Slot& slot : slots_) join(slot);
  }

  // One scripted event: a slot picked by the RNG leaves, or stops reading for 0.5
  // to 3 s (well inside the idle timeout: it must not be dropped for it).
  void scripted_event(Clock::time_point now) {
    const std::uint64_t r = rng_();
    Slot& slot = slots_[r % slots_.size()];
    if (!slot.joined()) return;
    if ((r >> 32) % 2 == 0) {
      leave(slot, now);
    } else if (slot.reading_at <= now) {
      slot.reading_at = now + std::chrono::milliseconds(500 + rng_() % 2500);
      ++tally_.stalls;
    }
  }

  // Everything each slot does in one pass: join when due, read when not stalled,
  // send the inputs up to a few ticks ahead of the newest tick seen.
  void pass(Clock::time_point now) {
    for (Slot& slot : slots_) {
      if (!slot.joined()) {
        if (now >= slot.rejoin_at) join(slot);
        continue;
      }
      client::Client& player = *slot.client;
      if (now >= slot.reading_at) read(player);
      if (player.state() != client::ConnectionState::Connected) {
        lost(slot, now);
        continue;
      }
      send_inputs(slot);
      if (player.state() != client::ConnectionState::Connected) lost(slot, now);
    }
  }

  void finish() {
    for (Slot& slot : slots_) {
      if (!slot.joined()) continue;
      read(*slot.client);
      tally_.view_desyncs += slot.client->stats().desyncs;
    }
  }

  // The slots holding a session (at the stop: the sessions the server shuts down).
  std::uint64_t joined() const {
    return static_cast<std::uint64_t>(std::count_if(
        slots_.begin(), slots_.end(), [](const Slot& slot) { return slot.joined(); }));
  }

  // After the server stopped: the clients go (their sessions ended as ShuttingDown).
  void close_all() {
    for (Slot& slot : slots_) slot.client.reset();
  }

 private:
  // The client reads only inside its own calls, and a call with a zero timeout runs
  // no socket handler: a 1 ms wait reads what has arrived, then the snapshots
  // already buffered are taken without waiting.
  void read(client::Client& player) {
    if (auto snapshot = player.next_snapshot(1ms)) take(*snapshot);
    while (player.buffered_snapshots() > 0) {
      if (auto snapshot = player.next_snapshot(0ms)) take(*snapshot);
    }
  }

  void take(const client::Snapshot& snapshot) {
    ++tally_.snapshots;
    tally_.global_tick = std::max(tally_.global_tick, snapshot.tick);
    ++tally_.hash_samples;
    const auto [it, inserted] = tally_.hashes.emplace(snapshot.tick, snapshot.state_hash);
    if (!inserted && it->second != snapshot.state_hash) ++tally_.cross_client_conflicts;
  }

  void send_inputs(Slot& slot) {
    const std::uint64_t lead = options_.lockstep ? 8 : 4;
    const std::uint64_t through = tally_.global_tick + lead;
    // At a fixed rate the ticks go on without us: a slot far behind skips to now.
    if (!options_.lockstep && slot.sent_through + 2 * lead < tally_.global_tick) {
      slot.sent_through = tally_.global_tick;
    }
    while (slot.sent_through < through) {
      ++slot.sent_through;
      const auto [ax, ay] = scripted_input(slot.index, slot.sent_through);
      if (!slot.client->send_input(slot.sent_through, ax, ay)) return;
    }
  }

  void lost(Slot& slot, Clock::time_point now) {
    ++tally_.lost_sessions;
    fmt::print(stderr, "physics-soak: slot {} lost its session: {}\n", slot.index,
               slot.client->last_error().to_string());
    tally_.view_desyncs += slot.client->stats().desyncs;
    slot.client.reset();
    slot.rejoin_at = now + 1s;
  }

  const Options& options_;
  server::Server& server_;
  std::mt19937_64 rng_;  // its output is fixed by the standard; no distributions used
  std::vector<Slot> slots_;
  Tally tally_;
};

// The tick-time quantile from the server's histogram: the upper bound of the bucket
// it falls in (infinity for the overflow bucket).
double histogram_quantile(const server::ServerStats& stats, double q) {
  std::uint64_t total = 0;
  for (const std::uint64_t count : stats.tick_seconds_buckets) total += count;
  if (total == 0) return 0.0;
  const auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(total)));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < stats.tick_seconds_buckets.size(); ++i) {
    seen += stats.tick_seconds_buckets[i];
    if (seen >= rank) {
      return i < server::kTickSecondsBounds.size() ? server::kTickSecondsBounds[i]
                                                   : std::numeric_limits<double>::infinity();
    }
  }
  return std::numeric_limits<double>::infinity();
}

struct ReplayCheck {
  bool read = false;
  std::string error;
  std::uint64_t ticks = 0;
  std::uint64_t recorded_mismatches = 0;  // the recording's own hashes against the replay
  std::uint64_t client_compared = 0;      // client hashes compared with the replay
  std::uint64_t client_mismatches = 0;
  std::uint64_t client_unreplayed = 0;  // ticks a client saw that the replay never reached
};

ReplayCheck replay_and_compare(const std::filesystem::path& path,
                               const std::map<std::uint64_t, std::uint64_t>& seen) {
  ReplayCheck result;
  auto opened = replay::Replayer::open(path);
  if (auto* error = std::get_if<recording::RecordingError>(&opened)) {
    result.error = error->to_string();
    return result;
  }
  replay::Replayer& replayer = *std::get<std::unique_ptr<replay::Replayer>>(opened);
  for (;;) {
    const replay::Replayer::Step step = replayer.step();
    if (step == replay::Replayer::Step::BadFile) {
      result.error = replayer.error().to_string();
      return result;
    }
    if (step == replay::Replayer::Step::End) break;
    const replay::TickCheck& check = replayer.last_check();
    ++result.ticks;
    if (check.diverged()) ++result.recorded_mismatches;
    if (const auto it = seen.find(check.tick); it != seen.end()) {
      ++result.client_compared;
      if (it->second != check.replayed_hash) {
        if (result.client_mismatches == 0) {
          fmt::print(stderr,
                     "physics-soak: DESYNC at tick {}: a client got {:016x}, replay {:016x}\n",
                     check.tick, it->second, check.replayed_hash);
        }
        ++result.client_mismatches;
      }
    }
  }
  for (const auto& [tick, hash] : seen) {
    if (tick > replayer.tick()) ++result.client_unreplayed;
  }
  result.read = true;
  return result;
}

// Session ends the tool causes or expects: its own Byes, the server's stop, and a
// join refused for want of room for another body. Every other reason is a drop the
// tool did not ask for.
const char* encoding_name(client::Encoding encoding) {
  switch (encoding) {
    case client::Encoding::Full:
      return "full";
    case client::Encoding::Exact:
      return "exact";
    case client::Encoding::Predicted:
      break;
  }
  return "predicted";
}

// Session ends the tool caused or expects, each up to the number it caused: its own
// leaves (a Bye; or Disconnected: a close with snapshots still unread makes the
// kernel send a reset, which the server may see before it reads the Bye),
// joins refused for want of room for another body, and the server's stop. Every
// other session end, and any beyond those counts, is a drop the tool did not ask for.
std::uint64_t unexplained_ends(const server::ServerStats& stats, const Tally& tally,
                               std::uint64_t joined_at_stop) {
  const auto count = [&](server::DropReason reason) -> std::uint64_t {
    const auto it = stats.dropped.find(reason);
    return it == stats.dropped.end() ? 0 : it->second;
  };
  const auto excess = [](std::uint64_t seen, std::uint64_t allowed) {
    return seen > allowed ? seen - allowed : 0;
  };
  using R = server::DropReason;
  std::uint64_t other = 0;
  for (const auto& [reason, n] : stats.dropped) {
    if (reason != R::ClientBye && reason != R::Disconnected && reason != R::NoSpawn &&
        reason != R::ShuttingDown) {
      other += n;
    }
  }
  return other + excess(count(R::ClientBye) + count(R::Disconnected), tally.leaves) +
         excess(count(R::NoSpawn), tally.join_refused_no_spawn) +
         excess(count(R::ShuttingDown), joined_at_stop);
}

int run(const Options& options) {
  auto loaded = scene::load_scene_file(options.scene_file);
  if (auto* error = std::get_if<scene::SceneError>(&loaded)) {
    fmt::print(stderr, "physics-soak: {}\n", error->to_string());
    return 2;
  }
  const scene::SceneDef scene = std::get<scene::SceneDef>(std::move(loaded));
  const std::filesystem::path record_path =
      options.record_path.empty()
          ? std::filesystem::temp_directory_path() / fmt::format("physics-soak-{}.rec", ::getpid())
          : std::filesystem::path(options.record_path);

  server::ServerConfig config;
  config.port = 0;
  config.lockstep = options.lockstep;
  // Realtime: a lockstep game's pace, so the tick budget means the same in both modes.
  config.lockstep_pace = server::ServerConfig::Pace::Realtime;
  config.max_clients = options.clients;
  // Every slot connects from 127.0.0.1: the per-address connect rate is for strangers.
  config.connects_per_second = 1000.0;
  config.connect_burst = 1000.0;
  config.record_path = record_path.string();
  auto server = std::make_unique<server::Server>(config, scene);
  std::thread server_thread([&] { server->run(); });

  Soak soak(options, *server);
  const auto start = Clock::now();
  soak.join_all();
  const auto end = start + std::chrono::milliseconds(static_cast<long>(options.duration * 1000));
  const auto warm = start + std::chrono::milliseconds(static_cast<long>(options.warmup * 1000));
  auto next_event = start + 250ms;
  auto next_sample = start;
  std::vector<std::pair<double, std::uint64_t>> rss;  // (seconds since start, bytes)
  std::uint64_t rss_at_warm = 0;
  server::ServerStats at_warm;
  bool warmed = false;
  std::size_t peak_input_bytes = 0;
  for (auto now = Clock::now(); now < end; now = Clock::now()) {
    soak.pass(now);
    if (now >= next_event) {
      soak.scripted_event(now);
      next_event += 250ms;
    }
    if (now >= next_sample) {
      const double t = std::chrono::duration<double>(now - start).count();
      rss.emplace_back(t, resident_bytes());
      const server::ServerStats stats = server->stats();
      peak_input_bytes = std::max(peak_input_bytes, stats.input_buffer_bytes);
      if (!warmed && now >= warm) {
        warmed = true;
        rss_at_warm = rss.back().second;
        at_warm = stats;
      }
      next_sample += 1s;
    }
  }
  soak.finish();
  const std::uint64_t rss_end = resident_bytes();
  // What the allocator holds freed but not returned, against what is still in use.
  ::malloc_trim(0);
  const std::uint64_t rss_trimmed = resident_bytes();
  const server::ServerStats before_stop = server->stats();
  const std::uint64_t joined_at_stop = soak.joined();
  server->stop();
  server_thread.join();
  const server::ServerStats stats = server->stats();
  soak.close_all();
  server.reset();  // closes the recording

  Tally& tally = soak.tally();
  const ReplayCheck replayed = replay_and_compare(record_path, tally.hashes);
  if (options.record_path.empty()) std::filesystem::remove(record_path);
  if (!replayed.read) {
    fmt::print(stderr, "physics-soak: the recording does not replay: {}\n", replayed.error);
    return 2;
  }

  const std::uint64_t unexplained =
      tally.lost_sessions + tally.join_failures + unexplained_ends(stats, tally, joined_at_stop);
  std::string drops;
  for (const auto& [reason, count] : stats.dropped) {
    drops += fmt::format("{}{} {}", drops.empty() ? "" : ", ", server::to_string(reason), count);
  }
  const std::uint64_t desyncs = replayed.client_mismatches + replayed.recorded_mismatches +
                                tally.cross_client_conflicts + replayed.client_unreplayed;

  std::uint64_t rss_max_after = 0;
  for (const auto& [t, bytes] : rss) {
    if (t >= options.warmup) rss_max_after = std::max(rss_max_after, bytes);
  }
  const auto growth = static_cast<std::int64_t>(rss_end) - static_cast<std::int64_t>(rss_at_warm);
  const auto trimmed_growth =
      static_cast<std::int64_t>(rss_trimmed) - static_cast<std::int64_t>(rss_at_warm);
  const auto peak_growth =
      static_cast<std::int64_t>(rss_max_after) - static_cast<std::int64_t>(rss_at_warm);
  const double budget_ms = 1000.0 / scene.tick_rate;
  const double p99_ms = 1000.0 * histogram_quantile(stats, 0.99);
  const double mean_ms = stats.ticks_stepped > 0 ? 1000.0 * stats.total_tick_seconds /
                                                       static_cast<double>(stats.ticks_stepped)
                                                 : 0.0;
  const double warm_ticks = static_cast<double>(stats.ticks_stepped - at_warm.ticks_stepped);
  const double mean_after_warm_ms =
      warm_ticks > 0 ? 1000.0 * (stats.total_tick_seconds - at_warm.total_tick_seconds) / warm_ticks
                     : 0.0;
  const char* mode = options.lockstep ? "lockstep" : "fixed-rate";

  fmt::print("physics-soak: {} on {}, {} slots, {} encoding, {:.0f} s, seed {}\n", mode, scene.name,
             options.clients, encoding_name(options.encoding), options.duration, options.seed);
  fmt::print("  ticks stepped {}, replayed {}; client hashes {} over {} ticks, all compared: {}\n",
             stats.ticks_stepped, replayed.ticks, tally.hash_samples, tally.hashes.size(),
             replayed.client_compared);
  fmt::print(
      "  desyncs {} (client vs replay {}, recording vs replay {}, between clients {}, beyond the "
      "replay {}); client view-hash resyncs {}\n",
      desyncs, replayed.client_mismatches, replayed.recorded_mismatches,
      tally.cross_client_conflicts, replayed.client_unreplayed, tally.view_desyncs);
  fmt::print(
      "  script: joins {}, leaves {}, read stalls {}; joins refused for no spawn room {}, "
      "other join failures {}, sessions lost {}\n",
      tally.joins, tally.leaves, tally.stalls, tally.join_refused_no_spawn, tally.join_failures,
      tally.lost_sessions);
  fmt::print(
      "  sessions ended by reason: {}; unexplained {} (a Bye or a reset for each of the tool's "
      "leaves, a refusal for each join without room, a shutdown for each client at the stop)\n",
      drops.empty() ? "none" : drops, unexplained);
  fmt::print(
      "  resident memory (whole process): {:.1f} MB at warm-up ({:.0f} s), {:.1f} MB at the end: "
      "growth {} bytes (peak after warm-up {} bytes)\n",
      static_cast<double>(rss_at_warm) / 1e6, options.warmup, static_cast<double>(rss_end) / 1e6,
      growth, peak_growth);
  // The resident set at each tenth of the time after warm-up: a leak climbs steadily,
  // an allocator settling steps up and stays.
  std::string trajectory;
  for (int tenth = 1; tenth <= 10; ++tenth) {
    const double at = options.warmup + (options.duration - options.warmup) * tenth / 10.0;
    std::uint64_t bytes = rss_end;
    for (const auto& [t, sampled] : rss) {
      if (t <= at) bytes = sampled;
    }
    trajectory += fmt::format("{}{:.1f}", tenth == 1 ? "" : " ", static_cast<double>(bytes) / 1e6);
  }
  fmt::print(
      "  resident memory at each tenth after warm-up, MB: {}; after malloc_trim: growth {} bytes "
      "(the tool's own record of {} ticks' hashes included)\n",
      trajectory, trimmed_growth, tally.hashes.size());
  fmt::print(
      "  server structures at the end: input buffers {} bytes (peak {}), views {}, peak queued "
      "snapshots {}, open connections {}\n",
      before_stop.input_buffer_bytes, peak_input_bytes, before_stop.views,
      stats.peak_queued_snapshots, before_stop.open_connections);
  fmt::print(
      "  tick time: p99 <= {:.3f} ms (histogram bound), mean {:.3f} ms ({:.3f} after warm-up), "
      "max {:.3f} ms; budget {:.3f} ms: p99 {}; overruns {}, dropped steps {}, skipped "
      "snapshots {}, lockstep timeouts {}\n",
      p99_ms, mean_ms, mean_after_warm_ms, 1000.0 * stats.max_tick_seconds, budget_ms,
      p99_ms <= budget_ms ? "within" : "OVER", stats.tick_overruns, stats.dropped_steps,
      stats.skipped_snapshots, stats.lockstep_timeouts);

  if (!options.csv_path.empty()) {
    const bool fresh = !std::filesystem::exists(options.csv_path) ||
                       std::filesystem::file_size(options.csv_path) == 0;
    std::FILE* csv = std::fopen(options.csv_path.c_str(), "a");
    if (csv == nullptr) {
      fmt::print(stderr, "physics-soak: cannot write {}\n", options.csv_path);
      return 2;
    }
    if (fresh) {
      fmt::print(csv,
                 "scene,mode,slots,seconds,seed,ticks,client_hashes,desyncs,joins,leaves,stalls,"
                 "no_spawn_refusals,unexplained_drops,rss_warm_bytes,rss_growth_bytes,"
                 "rss_peak_growth_bytes,rss_trimmed_growth_bytes,input_buffer_bytes_peak,tick_ms_"
                 "mean,tick_ms_p99_bound,"
                 "tick_ms_max,budget_ms,overruns,dropped_steps,skipped_snapshots\n");
    }
    fmt::print(csv,
               "{},{},{},{:.0f},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.4f},{:.4f},{:.4f},"
               "{:.4f},{},{},{}\n",
               scene.name, mode, options.clients, options.duration, options.seed,
               stats.ticks_stepped, tally.hash_samples, desyncs, tally.joins, tally.leaves,
               tally.stalls, tally.join_refused_no_spawn, unexplained, rss_at_warm, growth,
               peak_growth, trimmed_growth, peak_input_bytes, mean_ms, p99_ms,
               1000.0 * stats.max_tick_seconds, budget_ms, stats.tick_overruns, stats.dropped_steps,
               stats.skipped_snapshots);
    std::fclose(csv);
  }
  const bool ok = desyncs == 0 && unexplained == 0 && replayed.client_compared > 0;
  fmt::print("  result: {}\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "physics-soak: a long run of many clients joining, leaving and reading slowly, replayed "
      "at the end: zero desyncs, no unexplained drops, memory and tick time reported"};
  Options options;
  app.add_option("--scene", options.scene_file, "Scene file")->capture_default_str();
  app.add_flag("--lockstep", options.lockstep, "Lockstep (realtime pace) instead of a fixed rate");
  app.add_option("--duration", options.duration, "Seconds to run")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 86400.0));
  app.add_option("--warmup", options.warmup, "Seconds before memory growth is measured")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 86400.0));
  app.add_option("--clients", options.clients, "Client slots (and the server's max_clients)")
      ->capture_default_str()
      ->check(CLI::Range(1, 512));
  app.add_option("--seed", options.seed, "Seed of the script of joins, leaves and stalls")
      ->capture_default_str();
  std::string encoding = "predicted";
  app.add_option("--encoding", encoding, "The clients' snapshot encoding")
      ->capture_default_str()
      ->check(CLI::IsMember({"predicted", "exact", "full"}));
  app.add_option("--record", options.record_path,
                 "Keep the server's recording in this file (default: a temporary one)");
  app.add_option("--csv", options.csv_path,
                 "Append one CSV line of the figures to this file (a header first if new)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? 0 : 2;
  }
  options.encoding = encoding == "full"    ? client::Encoding::Full
                     : encoding == "exact" ? client::Encoding::Exact
                                           : client::Encoding::Predicted;
  if (options.warmup >= options.duration) {
    fmt::print(stderr, "physics-soak: --warmup must be shorter than --duration\n");
    return 2;
  }
  spdlog::set_level(spdlog::level::warn);
  try {
    return run(options);
  } catch (const std::exception& error) {
    fmt::print(stderr, "physics-soak: {}\n", error.what());
    return 2;
  }
}
