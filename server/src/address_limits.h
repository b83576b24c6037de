#pragma once
// What one address may cost us before its connections join: how fast it may open
// connections, and a growing refusal after repeated failed Hellos (bad token, bad
// version, malformed), so that guessing tokens or flooding the handshake from one
// machine is answered a few times and then refused at accept, cheaply. Socket-free
// and clock-free: the server passes the address and the time.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

#include "token_bucket.h"

namespace server {

struct AddressLimitsConfig {
  // Connections an address may open: this many a second, in bursts of connect_burst.
  double connects_per_second = 20.0;
  double connect_burst = 40.0;
  // After this many failed Hellos in a row an address is refused at accept for
  // backoff_base, doubled at each further failure, up to backoff_max. A Hello that
  // joins clears the count; so does a quiet backoff_max after the refusal ended.
  int failures_before_backoff = 8;
  std::chrono::milliseconds backoff_base{1000};
  std::chrono::milliseconds backoff_max{60000};
  // A player dropped for straggling or not reading: its address may not take a seat
  // for seat_backoff, doubled at each further drop, up to backoff_max; a quiet
  // backoff_max after the refusal ended forgives the drops.
  std::chrono::milliseconds seat_backoff{2000};
  // Addresses remembered at once; past it the longest-quiet one is forgotten.
  std::size_t max_tracked = 4096;
};

class AddressLimits {
 public:
  using clock = std::chrono::steady_clock;

  enum class Verdict : std::uint8_t { Allowed, TooFast, BackingOff };
  struct Decision {
    Verdict verdict = Verdict::Allowed;
    clock::duration retry_after{};  // when refused: how long until it may try again
  };

  explicit AddressLimits(AddressLimitsConfig config);

  // A new connection from `address`: counts it, and says whether to serve it.
  Decision on_accept(const std::string& address, clock::time_point now);
  void on_failed_hello(const std::string& address, clock::time_point now);
  void on_joined(const std::string& address);
  // A player from `address` dropped for straggling or for not reading.
  void on_player_dropped(const std::string& address, clock::time_point now);
  // How long until `address` may take a seat again (zero: now).
  clock::duration seat_wait(const std::string& address, clock::time_point now);

  std::size_t tracked() const { return entries_.size(); }
  int failures(const std::string& address) const;

 private:
  struct Entry {
    explicit Entry(const AddressLimitsConfig& config, clock::time_point now)
        : connects(config.connects_per_second, config.connect_burst, now), last_seen(now) {}
    TokenBucket connects;
    int failures = 0;
    clock::time_point refused_until{};
    clock::time_point last_failure{};
    clock::time_point last_seen;
    int player_drops = 0;
    clock::time_point seat_refused_until{};
  };
  Entry& entry(const std::string& address, clock::time_point now);
  // base * 2^times, at most backoff_max.
  clock::duration doubled(std::chrono::milliseconds base, int times) const;
  void forget_one();

  AddressLimitsConfig config_;
  std::map<std::string, Entry> entries_;
};

}  // namespace server
