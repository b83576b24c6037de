// What a stranger may cost us, socket-free and with explicit time: the token
// bucket behind the per-connection rate limits, the per-address connect rate and
// failed-Hello backoff, the per-cause log limit, and ids that skip live ones.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "address_limits.h"
#include "client_ids.h"
#include "log_limiter.h"
#include "token_bucket.h"
#include "wire.pb.h"

namespace {

using namespace std::chrono_literals;
using clock_type = std::chrono::steady_clock;
using server::AddressLimits;
using server::AddressLimitsConfig;
using server::LogLimiter;
using server::TokenBucket;

const clock_type::time_point kStart{std::chrono::seconds(1000)};

TEST(TokenBucket, ABurstPassesThenTheRateHolds) {
  TokenBucket bucket(100.0, 10.0, kStart);
  for (int i = 0; i < 10; ++i) {
    EXPECT_FALSE(bucket.in_debt(kStart)) << i;
    bucket.spend(1.0, kStart);
  }
  EXPECT_FALSE(bucket.in_debt(kStart));  // at zero, not below
  bucket.spend(1.0, kStart);
  EXPECT_TRUE(bucket.in_debt(kStart));
  // One token owed at 100 a second: 10 ms.
  const auto wait = bucket.wait(kStart);
  EXPECT_GE(wait, 10ms);
  EXPECT_LE(wait, 11ms);
  EXPECT_FALSE(bucket.in_debt(kStart + wait));
}

TEST(TokenBucket, RefillStopsAtTheBurst) {
  TokenBucket bucket(1000.0, 50.0, kStart);
  bucket.spend(50.0, kStart);
  EXPECT_DOUBLE_EQ(bucket.balance(kStart + 1h), 50.0);
}

TEST(TokenBucket, AnOverdraftIsPaidBackBeforeMore) {
  // A read's bytes are known only after it: one 64 KiB read against a 16 KiB burst.
  TokenBucket bucket(16384.0, 16384.0, kStart);
  bucket.spend(65536.0, kStart);
  EXPECT_TRUE(bucket.in_debt(kStart + 2s));
  EXPECT_FALSE(bucket.in_debt(kStart + 3s));
}

TEST(TokenBucket, ZeroRateIsUnlimited) {
  TokenBucket bucket(0.0, 0.0, kStart);
  bucket.spend(1e12, kStart);
  EXPECT_FALSE(bucket.in_debt(kStart));
  EXPECT_EQ(bucket.wait(kStart), clock_type::duration::zero());
}

AddressLimitsConfig backoff_config() {
  AddressLimitsConfig config;
  config.connects_per_second = 0.0;  // unlimited: these tests are about failures
  config.failures_before_backoff = 3;
  config.backoff_base = 1000ms;
  config.backoff_max = 8000ms;
  return config;
}

TEST(AddressLimits, FailedHellosBackOffDoublingUpToTheMaximum) {
  AddressLimits limits(backoff_config());
  const std::string attacker = "127.0.0.2";
  auto now = kStart;
  for (int i = 0; i < 2; ++i) {
    ASSERT_EQ(limits.on_accept(attacker, now).verdict, AddressLimits::Verdict::Allowed);
    limits.on_failed_hello(attacker, now);
  }
  ASSERT_EQ(limits.on_accept(attacker, now).verdict, AddressLimits::Verdict::Allowed);
  limits.on_failed_hello(attacker, now);  // the third: refused for 1 s
  const auto refused = limits.on_accept(attacker, now);
  EXPECT_EQ(refused.verdict, AddressLimits::Verdict::BackingOff);
  EXPECT_EQ(refused.retry_after, 1000ms);
  EXPECT_EQ(limits.on_accept(attacker, now + 999ms).verdict, AddressLimits::Verdict::BackingOff);
  now += 1000ms;
  ASSERT_EQ(limits.on_accept(attacker, now).verdict, AddressLimits::Verdict::Allowed);
  // Each further failure doubles it: 2, 4, 8, then 8 s again (the maximum).
  for (const auto expected : {2000ms, 4000ms, 8000ms, 8000ms}) {
    limits.on_failed_hello(attacker, now);
    const auto decision = limits.on_accept(attacker, now);
    EXPECT_EQ(decision.verdict, AddressLimits::Verdict::BackingOff);
    EXPECT_EQ(decision.retry_after, expected);
    now += expected;
  }
  // Another address is not touched by any of it.
  EXPECT_EQ(limits.on_accept("127.0.0.1", now - 1ms).verdict, AddressLimits::Verdict::Allowed);
}

TEST(AddressLimits, AJoinClearsTheCount) {
  AddressLimits limits(backoff_config());
  limits.on_failed_hello("10.0.0.1", kStart);
  limits.on_failed_hello("10.0.0.1", kStart);
  limits.on_joined("10.0.0.1");
  EXPECT_EQ(limits.failures("10.0.0.1"), 0);
  limits.on_failed_hello("10.0.0.1", kStart);
  EXPECT_EQ(limits.on_accept("10.0.0.1", kStart).verdict, AddressLimits::Verdict::Allowed);
}

TEST(AddressLimits, AQuietMaximumForgivesTheFailures) {
  AddressLimits limits(backoff_config());
  for (int i = 0; i < 3; ++i) limits.on_failed_hello("10.0.0.1", kStart);
  // Refused until +1 s; the count stays for 8 s (the maximum) after that.
  EXPECT_EQ(limits.on_accept("10.0.0.1", kStart + 8999ms).verdict, AddressLimits::Verdict::Allowed);
  EXPECT_EQ(limits.failures("10.0.0.1"), 3);
  EXPECT_EQ(limits.on_accept("10.0.0.1", kStart + 9000ms).verdict, AddressLimits::Verdict::Allowed);
  EXPECT_EQ(limits.failures("10.0.0.1"), 0);
}

TEST(AddressLimits, ConnectsAreRateLimitedPerAddress) {
  AddressLimitsConfig config;
  config.connects_per_second = 10.0;
  config.connect_burst = 5.0;
  AddressLimits limits(config);
  int allowed = 0;
  for (int i = 0; i < 100; ++i) {
    allowed += limits.on_accept("10.0.0.9", kStart).verdict == AddressLimits::Verdict::Allowed;
  }
  EXPECT_EQ(allowed, 6);  // the burst, and the one that overdraws it
  const auto refused = limits.on_accept("10.0.0.9", kStart);
  EXPECT_EQ(refused.verdict, AddressLimits::Verdict::TooFast);
  EXPECT_GT(refused.retry_after, 0ms);
  EXPECT_EQ(limits.on_accept("10.0.0.8", kStart).verdict, AddressLimits::Verdict::Allowed);
  EXPECT_EQ(limits.on_accept("10.0.0.9", kStart + 1s).verdict, AddressLimits::Verdict::Allowed);
}

TEST(AddressLimits, MemoryIsBoundedAndABackedOffAddressIsKept) {
  AddressLimitsConfig config = backoff_config();
  config.max_tracked = 16;
  AddressLimits limits(config);
  for (int i = 0; i < 3; ++i) limits.on_failed_hello("attacker", kStart);
  // Many other addresses come and go: the table stays at its bound, and the
  // attacker's backoff is not washed out by them.
  for (int i = 0; i < 1000; ++i) {
    limits.on_accept("other-" + std::to_string(i), kStart + std::chrono::microseconds(i));
  }
  EXPECT_LE(limits.tracked(), 16u);
  EXPECT_EQ(limits.on_accept("attacker", kStart + 1ms).verdict, AddressLimits::Verdict::BackingOff);
}

TEST(LogLimiter, AdmitsAFewLinesPerCauseAndCountsTheRest) {
  LogLimiter limiter(3, 1s);
  int admitted = 0;
  for (int i = 0; i < 100; ++i)
    admitted += limiter.admit("connection", kStart, "10.0.0." + std::to_string(i % 60));
  EXPECT_EQ(admitted, 3);
  EXPECT_TRUE(limiter.admit("refused", kStart));  // another cause has its own share
  std::vector<std::pair<std::string, std::uint64_t>> reported;
  std::size_t addresses = 0;
  auto report = [&](const std::string& cause, std::uint64_t n, std::size_t from) {
    reported.emplace_back(cause, n);
    addresses = from;
  };
  limiter.flush(kStart + 500ms, report);
  EXPECT_TRUE(reported.empty());  // the window is not over yet
  limiter.flush(kStart + 1s, report);
  ASSERT_EQ(reported.size(), 1u);
  EXPECT_EQ(reported[0].first, "connection");
  EXPECT_EQ(reported[0].second, 97u);
  EXPECT_EQ(addresses, 60u);  // the 97 suppressed lines came from 60 addresses
  EXPECT_EQ(limiter.suppressed_total(), 97u);
  // A fresh window admits again.
  EXPECT_TRUE(limiter.admit("connection", kStart + 1100ms));
}

// A Hello whose name is not UTF-8 fails to parse; libprotobuf would log a line for
// it on stderr, for every such frame a stranger sends.
TEST(LogLimiter, LibprotobufsPerFrameLogIsSilenced) {
  server::silence_protobuf_log();
  physics::wire::ClientMessage hello;
  hello.mutable_hello()->set_client_name("ok");
  std::string bytes = hello.SerializeAsString();
  const auto at = bytes.find("ok");
  ASSERT_NE(at, std::string::npos);
  bytes[at] = static_cast<char>(0xFF);  // not UTF-8
  physics::wire::ClientMessage parsed;
  ::testing::internal::CaptureStderr();
  const bool ok = parsed.ParseFromString(bytes);
  const std::string logged = ::testing::internal::GetCapturedStderr();
  EXPECT_FALSE(ok);
  EXPECT_EQ(logged, "");
}

TEST(ClientIds, TheCounterWrapsPastZeroAndLiveIds) {
  const std::set<std::uint32_t> live = {std::numeric_limits<std::uint32_t>::max(), 1, 2, 4};
  auto is_live = [&](std::uint32_t id) { return live.count(id) > 0; };
  std::uint32_t next = std::numeric_limits<std::uint32_t>::max() - 1;
  EXPECT_EQ(server::take_free_id(next, is_live), std::numeric_limits<std::uint32_t>::max() - 1);
  // max is live, 0 is never used, 1 and 2 are live.
  EXPECT_EQ(server::take_free_id(next, is_live), 3u);
  EXPECT_EQ(server::take_free_id(next, is_live), 5u);
  EXPECT_EQ(next, 6u);
}

}  // namespace
