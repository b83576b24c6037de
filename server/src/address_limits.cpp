#include "address_limits.h"

#include <algorithm>
#include <stdexcept>

namespace server {

AddressLimits::AddressLimits(AddressLimitsConfig config) : config_(config) {
  if (config_.failures_before_backoff < 1) {
    throw std::invalid_argument("failures before backoff must be at least 1");
  }
  if (config_.max_tracked < 1) throw std::invalid_argument("max_tracked must be at least 1");
}

AddressLimits::Entry& AddressLimits::entry(const std::string& address, clock::time_point now) {
  auto it = entries_.find(address);
  if (it == entries_.end()) {
    if (entries_.size() >= config_.max_tracked) forget_one();
    it = entries_.emplace(address, Entry(config_, now)).first;
  }
  Entry& found = it->second;
  found.last_seen = now;
  // A quiet backoff_max, after the last failure and the last refusal, forgives what
  // the address failed before.
  if (found.failures > 0 &&
      now - std::max(found.last_failure, found.refused_until) >= config_.backoff_max) {
    found.failures = 0;
  }
  if (found.player_drops > 0 && now - found.seat_refused_until >= config_.backoff_max) {
    found.player_drops = 0;
  }
  return found;
}

// The address quiet longest goes; one still refused is kept if any other can go, so
// that an attacker cannot wash its own backoff out by connecting from many others.
void AddressLimits::forget_one() {
  auto victim = entries_.end();
  bool victim_refused = true;
  for (auto it = entries_.begin(); it != entries_.end(); ++it) {
    const bool refused =
        it->second.failures >= config_.failures_before_backoff || it->second.player_drops > 0;
    if (victim == entries_.end() || (victim_refused && !refused) ||
        (victim_refused == refused && it->second.last_seen < victim->second.last_seen)) {
      victim = it;
      victim_refused = refused;
    }
  }
  if (victim != entries_.end()) entries_.erase(victim);
}

AddressLimits::Decision AddressLimits::on_accept(const std::string& address,
                                                 clock::time_point now) {
  Entry& e = entry(address, now);
  Decision decision;
  if (now < e.refused_until) {
    decision.verdict = Verdict::BackingOff;
    decision.retry_after = e.refused_until - now;
    return decision;
  }
  if (e.connects.in_debt(now)) {
    decision.verdict = Verdict::TooFast;
    decision.retry_after = e.connects.wait(now);
    return decision;
  }
  e.connects.spend(1.0, now);
  return decision;
}

void AddressLimits::on_failed_hello(const std::string& address, clock::time_point now) {
  Entry& e = entry(address, now);
  e.last_failure = now;
  ++e.failures;
  const int over = e.failures - config_.failures_before_backoff;
  if (over < 0) return;
  e.refused_until = now + doubled(config_.backoff_base, over);
}

AddressLimits::clock::duration AddressLimits::doubled(std::chrono::milliseconds base,
                                                      int times) const {
  // base * 2^times, computed without overflowing: stop doubling at the maximum.
  auto value = std::chrono::duration_cast<clock::duration>(base);
  const auto most = std::chrono::duration_cast<clock::duration>(config_.backoff_max);
  for (int i = 0; i < times && value < most; ++i) value *= 2;
  return std::min(value, most);
}

void AddressLimits::on_player_dropped(const std::string& address, clock::time_point now) {
  Entry& e = entry(address, now);
  e.seat_refused_until = now + doubled(config_.seat_backoff, e.player_drops);
  ++e.player_drops;
}

AddressLimits::clock::duration AddressLimits::seat_wait(const std::string& address,
                                                        clock::time_point now) {
  const auto it = entries_.find(address);
  if (it == entries_.end() || now >= it->second.seat_refused_until) return {};
  return it->second.seat_refused_until - now;
}

void AddressLimits::on_joined(const std::string& address) {
  const auto it = entries_.find(address);
  if (it != entries_.end()) it->second.failures = 0;
}

int AddressLimits::failures(const std::string& address) const {
  const auto it = entries_.find(address);
  return it == entries_.end() ? 0 : it->second.failures;
}

}  // namespace server
