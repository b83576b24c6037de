// physics-netsim: the link conditioner of physics::testing on the command line. It
// listens on a loopback port and relays every connection to a target (a
// physics-server, say) with the latency, jitter, bandwidth and stalls of a real path,
// until SIGINT or SIGTERM; then it prints what it relayed on stderr.
#include <pthread.h>
#include <signal.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics_testing/link_conditioner.h"

namespace {

// Exit codes: 0 stopped by a signal, 1 could not listen, 2 bad flags.
constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

// The longest latency, jitter or stall a flag takes: ten minutes.
constexpr double kMaxMs = 600000.0;

std::chrono::microseconds from_ms(double ms) {
  return std::chrono::microseconds(std::llround(ms * 1000.0));
}

// "HOST:PORT", "[HOST]:PORT" or an IPv6 address and port as "::1:7777".
std::optional<std::pair<std::string, std::uint16_t>> split_host_port(const std::string& text) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) return std::nullopt;
  std::string host = text.substr(0, colon);
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') {
    host = host.substr(1, host.size() - 2);
  }
  const std::string digits = text.substr(colon + 1);
  if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 5) {
    return std::nullopt;
  }
  const int port = std::stoi(digits);
  if (port < 1 || port > 65535) return std::nullopt;
  return std::make_pair(host, static_cast<std::uint16_t>(port));
}

// CLI11's Range lets NaN through (every comparison with it is false).
const CLI::Validator kFinite(
    [](const std::string& text) {
      double value = 0.0;
      return CLI::detail::lexical_cast(text, value) && std::isfinite(value)
                 ? std::string()
                 : "not a finite number: " + text;
    },
    "FINITE");

// The flags as given, before they are checked and turned into the relay's config.
struct NetsimFlags {
  physics_testing::LinkConditionerConfig config;
  int listen_port = 0;
  std::string to;
  double latency_ms = 0.0;
  std::optional<double> latency_up_ms;
  std::optional<double> latency_down_ms;
  double jitter_ms = 0.0;
  double bandwidth_kbps = 0.0;
  double stall_ms = 0.0;
  double stall_every_ms = 0.0;
  double stall_rate = 0.0;
  std::vector<double> stall_at_ms;
  std::string stall_direction = "both";
  std::uint64_t seed = config.path.seed;
};

void add_flags(CLI::App& app, NetsimFlags& flags) {
  // --port and --bind as physics-server has them, so that physics::testing's
  // ServerProcess can run the relay as it runs a server.
  app.add_option("--listen,--port", flags.listen_port,
                 "Port to listen on; 0 picks a free one (printed as 'listening on "
                 "ADDRESS:PORT')")
      ->capture_default_str()
      ->check(CLI::Range(0, 65535));
  app.add_option("--bind", flags.config.listen_host,
                 "Loopback address to listen on (127.0.0.0/8, ::1)")
      ->capture_default_str();
  app.add_option("--to", flags.to, "Where to relay each connection: HOST:PORT on loopback")
      ->required();
  app.add_option("--latency-ms", flags.latency_ms, "One-way latency, both directions")
      ->capture_default_str()
      ->check(kFinite)
      ->check(CLI::Range(0.0, kMaxMs));
  app.add_option("--latency-up-ms", flags.latency_up_ms,
                 "One-way latency to the target (client to server); default: --latency-ms")
      ->check(kFinite)
      ->check(CLI::Range(0.0, kMaxMs));
  app.add_option("--latency-down-ms", flags.latency_down_ms,
                 "One-way latency back (server to client); default: --latency-ms")
      ->check(kFinite)
      ->check(CLI::Range(0.0, kMaxMs));
  app.add_option("--jitter-ms", flags.jitter_ms,
                 "Extra delay drawn uniformly from [0, this] per chunk, both directions; "
                 "order is kept")
      ->capture_default_str()
      ->check(kFinite)
      ->check(CLI::Range(0.0, kMaxMs));
  app.add_option("--bandwidth-kbps", flags.bandwidth_kbps,
                 "Bandwidth cap per direction in kilobits per second; 0: no cap")
      ->capture_default_str()
      ->check(kFinite)
      ->check(CLI::Range(0.0, 1e9));
  app.add_option("--stall-ms", flags.stall_ms,
                 "How long a stall holds the stream (about TCP's retransmission timeout, "
                 "200 ms and more); needs --stall-every-ms, --stall-rate or --stall-at-ms")
      ->check(kFinite)
      ->check(CLI::Range(0.0, kMaxMs));
  app.add_option("--stall-every-ms", flags.stall_every_ms,
                 "A stall every this long from each connection's start")
      ->check(kFinite)
      ->check(CLI::Range(0.0, 86400000.0));
  app.add_option("--stall-rate", flags.stall_rate,
                 "Random stalls (Poisson) at this mean rate per second of connection time")
      ->check(kFinite)
      ->check(CLI::Range(0.0, 1000.0));
  app.add_option("--stall-at-ms", flags.stall_at_ms,
                 "Stalls at these times from each connection's start (comma-separated)")
      ->delimiter(',')
      ->check(kFinite)
      ->check(CLI::Range(0.0, 86400000.0));
  app.add_option("--stall-direction", flags.stall_direction,
                 "Which directions stall: both, up (to the target) or down")
      ->capture_default_str()
      ->check(CLI::IsMember({"both", "up", "down"}));
  app.add_option("--max-held-bytes", flags.config.max_held_bytes,
                 "Bytes held in one direction before the relay stops reading its sender")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{1}, std::size_t{1} << 32));
  app.add_option("--seed", flags.seed,
                 "Seed of the jitter and the random stalls (connection k: seed + k)")
      ->capture_default_str();
}

// Fills flags.config from the other flags, or says on stderr why they do not go
// together and returns false.
bool to_config(NetsimFlags& flags) {
  const auto target = split_host_port(flags.to);
  if (!target) {
    std::cerr << "physics-netsim: --to must be HOST:PORT with a port in 1 to 65535: " << flags.to
              << "\n";
    return false;
  }
  const bool stall_source =
      flags.stall_every_ms > 0.0 || flags.stall_rate > 0.0 || !flags.stall_at_ms.empty();
  if ((flags.stall_ms > 0.0) != stall_source) {
    std::cerr << "physics-netsim: --stall-ms goes with --stall-every-ms, --stall-rate or "
                 "--stall-at-ms, and each of those with --stall-ms\n";
    return false;
  }

  flags.config.listen_port = static_cast<std::uint16_t>(flags.listen_port);
  flags.config.target_host = target->first;
  flags.config.target_port = target->second;
  physics_testing::PathConfig& path = flags.config.path;
  path.to_server.latency = from_ms(flags.latency_up_ms.value_or(flags.latency_ms));
  path.to_client.latency = from_ms(flags.latency_down_ms.value_or(flags.latency_ms));
  path.to_server.jitter = path.to_client.jitter = from_ms(flags.jitter_ms);
  path.to_server.bandwidth_bytes_per_second = path.to_client.bandwidth_bytes_per_second =
      flags.bandwidth_kbps * 1000.0 / 8.0;
  path.stalls.duration = std::chrono::milliseconds(std::llround(flags.stall_ms));
  path.stalls.every = std::chrono::milliseconds(std::llround(flags.stall_every_ms));
  path.stalls.per_second = flags.stall_rate;
  for (const double at : flags.stall_at_ms) {
    path.stalls.at.push_back(std::chrono::milliseconds(std::llround(at)));
  }
  path.stalls.to_server = flags.stall_direction != "down";
  path.stalls.to_client = flags.stall_direction != "up";
  path.seed = flags.seed;

  return true;
}

// Relays until SIGINT or SIGTERM, then prints what it relayed; the exit code.
int relay_until_stopped(const physics_testing::LinkConditionerConfig& config) {
  // The signals are taken by sigwait below; blocked before the relay's thread starts,
  // so that they are blocked there too.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  try {
    physics_testing::LinkConditioner relay(config);
    // Tests and scripts read this line to learn the port (--listen 0).
    std::cout << "listening on " << config.listen_host << ":" << relay.port() << std::endl;
    int signal_number = 0;
    sigwait(&stop_signals, &signal_number);
    const physics_testing::LinkStats stats = relay.stats();
    std::cerr << "physics-netsim: " << stats.connections << " connections; "
              << stats.bytes_to_server << " bytes to the target, " << stats.bytes_to_client
              << " bytes back; " << stats.stalls << " stalls; at most " << stats.held_bytes_peak
              << " bytes held in one direction\n";
  } catch (const std::invalid_argument& error) {
    std::cerr << "physics-netsim: " << error.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& error) {
    std::cerr << "physics-netsim: " << error.what() << "\n";
    return kExitFailure;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "physics-netsim: a TCP relay on loopback that delivers each direction's bytes as a real "
      "path would (latency, jitter, bandwidth cap, stalls); see docs/NETSIM.md"};
  NetsimFlags flags;
  add_flags(app, flags);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? 0 : kExitUsage;
  }
  if (!to_config(flags)) return kExitUsage;
  return relay_until_stopped(flags.config);
}
