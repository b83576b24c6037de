// The link conditioner over real loopback sockets: a sender, the relay, and a target
// this test drives itself. Every bound on time is a stated margin; lower bounds are
// exact (the relay must never deliver early), upper bounds allow for scheduling.
#include "physics_testing/link_conditioner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <future>
#include <iostream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "loopback_sockets.h"

namespace physics_testing {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
using test::connect_loopback;
using test::Listener;
using test::Socket;

// One scheduling quantum: how much later than its due time the best of a few small
// messages may arrive (the relay's timer, its write, the receiver's wakeup).
constexpr auto kSchedulingQuantum = 5ms;
// How much later than due any single message may arrive on a busy machine (a test
// shares two cores with builds): a bound that still fails if the relay adds a
// latency of its own.
constexpr auto kBusyMachineSlack = 60ms;
// Long enough for anything on loopback that the test waits for.
constexpr auto kDeadline = 5s;

// A conditioned path between a client socket and a target socket of this test.
struct ConditionedLink {
  explicit ConditionedLink(PathConfig path, std::size_t max_held_bytes = 4u << 20)
      : relay(config(target_listener.port(), std::move(path), max_held_bytes)) {
    connect_began = Clock::now();
    client = connect_loopback(relay.port());
    target = target_listener.accept(2s);
  }

  static LinkConditionerConfig config(std::uint16_t target_port, PathConfig path,
                                      std::size_t max_held_bytes) {
    LinkConditionerConfig config;
    config.target_port = target_port;
    config.path = std::move(path);
    config.max_held_bytes = max_held_bytes;
    return config;
  }

  Listener target_listener;
  LinkConditioner relay;
  Clock::time_point connect_began;  // no later than the relay's connection began
  Socket client;
  Socket target;
};

// The time one small message takes from `from` to `to`.
Clock::duration one_way(const Socket& from, const Socket& to) {
  static const std::vector<std::uint8_t> message = {1, 2, 3, 4, 5, 6, 7, 8};
  const Clock::time_point sent = Clock::now();
  EXPECT_TRUE(from.send_all(message));
  const auto received = to.receive(message.size(), Clock::now() + kDeadline);
  EXPECT_EQ(received, message);
  return Clock::now() - sent;
}

std::vector<std::uint8_t> random_bytes(std::size_t count, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::vector<std::uint8_t> bytes(count);
  for (std::uint8_t& byte : bytes) byte = static_cast<std::uint8_t>(random() >> 56);
  return bytes;
}

std::int64_t ms(Clock::duration duration) {
  return std::chrono::duration_cast<std::chrono::milliseconds>(duration).count();
}

std::int64_t us(Clock::duration duration) {
  return std::chrono::duration_cast<std::chrono::microseconds>(duration).count();
}

TEST(LinkConditioner, DeliversEveryByteInOrderBothWaysWithJitterAndForwardsTheEnd) {
  ConditionedLink link(symmetric_path(1ms, 3ms));
  ASSERT_TRUE(link.client && link.target);
  const std::vector<std::uint8_t> up = random_bytes(1u << 20, 11);
  const std::vector<std::uint8_t> down = random_bytes(1u << 20, 12);

  auto send_up = std::async(std::launch::async, [&] {
    const bool sent = link.client.send_all(up);
    link.client.shutdown_send();
    return sent;
  });
  auto send_down = std::async(std::launch::async, [&] {
    const bool sent = link.target.send_all(down);
    link.target.shutdown_send();
    return sent;
  });
  auto received_down = std::async(std::launch::async, [&] {
    return link.client.receive(down.size(), Clock::now() + kDeadline);
  });
  const auto received_up = link.target.receive(up.size(), Clock::now() + kDeadline);

  EXPECT_TRUE(send_up.get());
  EXPECT_TRUE(send_down.get());
  ASSERT_TRUE(received_up.has_value());
  EXPECT_TRUE(*received_up == up) << "the bytes to the target differ from those sent";
  const auto down_bytes = received_down.get();
  ASSERT_TRUE(down_bytes.has_value());
  EXPECT_TRUE(*down_bytes == down) << "the bytes back differ from those sent";
  // Each FIN comes after the last byte.
  EXPECT_TRUE(link.target.receive_end(Clock::now() + kDeadline));
  EXPECT_TRUE(link.client.receive_end(Clock::now() + kDeadline));

  const LinkStats stats = link.relay.stats();
  EXPECT_EQ(stats.connections, 1u);
  EXPECT_EQ(stats.bytes_to_server, up.size());
  EXPECT_EQ(stats.bytes_to_client, down.size());
  EXPECT_EQ(stats.stalls, 0u);
}

TEST(LinkConditioner, ASmallMessageTakesTheSetLatencyEachWayPlusAtMostOneQuantum) {
  PathConfig path;
  path.to_server.latency = 30ms;
  path.to_client.latency = 20ms;
  ConditionedLink link(path);
  ASSERT_TRUE(link.client && link.target);
  constexpr int kSamples = 5;
  Clock::duration best_up = Clock::duration::max();
  Clock::duration best_down = Clock::duration::max();
  // What the relay adds to the set latency, printed for docs/NETSIM.md's accuracy.
  std::string late = "late by (us), to the target / back:";
  for (int i = 0; i < kSamples; ++i) {
    const Clock::duration up = one_way(link.client, link.target);
    const Clock::duration down = one_way(link.target, link.client);
    // Never earlier than set, not one sample.
    EXPECT_GE(up, 30ms) << "sample " << i;
    EXPECT_GE(down, 20ms) << "sample " << i;
    EXPECT_LE(up, 30ms + kBusyMachineSlack) << "sample " << i;
    EXPECT_LE(down, 20ms + kBusyMachineSlack) << "sample " << i;
    best_up = std::min(best_up, up);
    best_down = std::min(best_down, down);
    late += " " + std::to_string(us(up - 30ms)) + "/" + std::to_string(us(down - 20ms));
  }
  std::cout << late << "\n";
  EXPECT_LE(best_up, 30ms + kSchedulingQuantum) << ms(best_up) << " ms";
  EXPECT_LE(best_down, 20ms + kSchedulingQuantum) << ms(best_down) << " ms";
}

TEST(LinkConditioner, JitterDelaysMessagesUnevenlyButKeepsTheirOrder) {
  constexpr auto kLatency = 5ms;
  constexpr auto kJitter = 30ms;
  constexpr std::uint32_t kMessages = 100;
  ConditionedLink link(symmetric_path(kLatency, kJitter));
  ASSERT_TRUE(link.client && link.target);
  std::vector<Clock::time_point> sent_at(kMessages);
  auto sender = std::async(std::launch::async, [&] {
    for (std::uint32_t i = 0; i < kMessages; ++i) {
      const std::uint8_t message[4] = {static_cast<std::uint8_t>(i),
                                       static_cast<std::uint8_t>(i >> 8), 0xAB, 0xCD};
      sent_at[i] = Clock::now();
      if (!link.client.send_all(message)) return false;
      std::this_thread::sleep_for(1ms);  // paces the sender: one message a read
    }
    return true;
  });
  std::vector<Clock::duration> delays;
  for (std::uint32_t i = 0; i < kMessages; ++i) {
    const auto message = link.target.receive(4, Clock::now() + kDeadline);
    ASSERT_TRUE(message.has_value()) << "message " << i;
    const Clock::time_point arrived = Clock::now();
    const std::uint32_t number = (*message)[0] | ((*message)[1] << 8);
    ASSERT_EQ(number, i) << "out of order";
    EXPECT_EQ((*message)[2], 0xAB);
    EXPECT_EQ((*message)[3], 0xCD);
    delays.push_back(arrived - sent_at[i]);
  }
  ASSERT_TRUE(sender.get());
  for (std::size_t i = 0; i < delays.size(); ++i) EXPECT_GE(delays[i], kLatency) << "message " << i;
  // 100 draws from [0, 30 ms]: some land in the upper half (all below it by chance:
  // 2^-100); order only ever adds delay.
  const Clock::duration longest = *std::max_element(delays.begin(), delays.end());
  EXPECT_GE(longest, kLatency + kJitter / 2) << ms(longest) << " ms";
}

TEST(LinkConditioner, AScriptedStallHoldsTheStreamForItsDuration) {
  constexpr auto kStallAt = 150ms;
  constexpr auto kStall = 300ms;
  // Beyond kBusyMachineSlack: the relay's connection may begin a little after the
  // test's connect began.
  constexpr auto kStallMargin = kBusyMachineSlack + 10ms;
  PathConfig path;
  path.stalls.duration = kStall;
  path.stalls.at = {kStallAt};
  path.stalls.to_client = false;
  ConditionedLink link(path);
  ASSERT_TRUE(link.client && link.target);

  // Before the stall: through at once.
  EXPECT_LE(one_way(link.client, link.target), kBusyMachineSlack);
  // Sent in the stall, 50 ms after it began: held until it ends.
  std::this_thread::sleep_until(link.connect_began + kStallAt + 50ms);
  const Clock::time_point stall_began = link.connect_began + kStallAt;
  const std::vector<std::uint8_t> message = {42};
  ASSERT_TRUE(link.client.send_all(message));
  // The other direction does not stall.
  EXPECT_LE(one_way(link.target, link.client), kBusyMachineSlack);
  ASSERT_EQ(link.target.receive(1, Clock::now() + kDeadline), message);
  const Clock::duration held = Clock::now() - stall_began;
  std::cout << "a " << ms(kStall) << " ms stall held the stream " << us(held) << " us\n";
  EXPECT_GE(held, kStall) << ms(held) << " ms";
  EXPECT_LE(held, kStall + kStallMargin) << ms(held) << " ms";
  EXPECT_EQ(link.relay.stats().stalls, 1u);
}

TEST(LinkConditioner, ABandwidthCapMakesNBytesTakeAtLeastNOverTheBandwidth) {
  constexpr double kBytesPerSecond = 200000.0;
  constexpr std::size_t kBytes = 40000;  // 200 ms on the wire
  constexpr auto kOnWire = 200ms;
  constexpr auto kBandwidthMargin = 100ms;
  PathConfig path;
  path.to_server.bandwidth_bytes_per_second = kBytesPerSecond;
  ConditionedLink link(path);
  ASSERT_TRUE(link.client && link.target);
  const std::vector<std::uint8_t> bytes = random_bytes(kBytes, 3);
  const Clock::time_point began = Clock::now();
  auto sender = std::async(std::launch::async, [&] { return link.client.send_all(bytes); });
  const auto received = link.target.receive(kBytes, Clock::now() + kDeadline);
  const Clock::duration took = Clock::now() - began;
  std::cout << kBytes << " bytes at " << kBytesPerSecond << " B/s took " << us(took) << " us\n";
  ASSERT_TRUE(sender.get());
  ASSERT_TRUE(received.has_value());
  EXPECT_TRUE(*received == bytes);
  EXPECT_GE(took, kOnWire) << ms(took) << " ms";
  EXPECT_LE(took, kOnWire + kBandwidthMargin) << ms(took) << " ms";
  // The cap is per direction: the way back is not capped.
  EXPECT_LE(one_way(link.target, link.client), kBusyMachineSlack);
}

TEST(LinkConditioner, SetPathChangesTheLatencyOfLaterBytes) {
  ConditionedLink link(symmetric_path(10ms));
  ASSERT_TRUE(link.client && link.target);
  const Clock::duration before = one_way(link.client, link.target);
  EXPECT_GE(before, 10ms);
  EXPECT_LT(before, 60ms);
  link.relay.set_path(symmetric_path(60ms));
  const Clock::duration up = one_way(link.client, link.target);
  const Clock::duration down = one_way(link.target, link.client);
  EXPECT_GE(up, 60ms) << ms(up) << " ms";
  EXPECT_GE(down, 60ms) << ms(down) << " ms";
  EXPECT_LE(up, 60ms + kBusyMachineSlack) << ms(up) << " ms";
  // A new connection gets the new path too.
  Socket second_client = connect_loopback(link.relay.port());
  Socket second_target = link.target_listener.accept(2s);
  ASSERT_TRUE(second_client && second_target);
  EXPECT_GE(one_way(second_client, second_target), 60ms);
  EXPECT_EQ(link.relay.stats().connections, 2u);
}

TEST(LinkConditioner, ASenderIntoATargetThatDoesNotReadMeetsBackPressure) {
  constexpr std::size_t kMaxHeld = 64 * 1024;
  ConditionedLink link(PathConfig{}, kMaxHeld);
  ASSERT_TRUE(link.client && link.target);
  // More than every socket buffer on the way can take (at most 4 MiB to send and
  // 32 MiB to receive on this machine's defaults, a socket pair at each end).
  std::vector<std::uint8_t> bytes(80u << 20);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    bytes[i] = static_cast<std::uint8_t>((i * 2654435761u) >> 13);
  }
  const std::size_t sent = link.client.send_until_full(bytes, 300ms);
  EXPECT_LT(sent, bytes.size()) << "the path never filled";
  const LinkStats full = link.relay.stats();
  EXPECT_EQ(full.held_bytes_peak, kMaxHeld) << "the relay held more, or never filled";
  // Reading now brings every byte sent, in order.
  const auto received = link.target.receive(sent, Clock::now() + kDeadline);
  ASSERT_TRUE(received.has_value());
  EXPECT_TRUE(std::equal(received->begin(), received->end(), bytes.begin()));
  EXPECT_LE(link.relay.stats().held_bytes_peak, kMaxHeld);
}

TEST(LinkConditioner, ATargetThatRefusesClosesTheClient) {
  std::uint16_t closed_port = 0;
  {
    Listener gone;
    closed_port = gone.port();
  }
  LinkConditionerConfig config;
  config.target_port = closed_port;
  LinkConditioner relay(config);
  Socket client = connect_loopback(relay.port());
  ASSERT_TRUE(client);
  EXPECT_TRUE(client.receive_end(Clock::now() + kDeadline));
}

TEST(LinkConditioner, RefusesAddressesOffLoopbackAndBadSettings) {
  const auto refused = [](const LinkConditionerConfig& config) {
    try {
      LinkConditioner relay(config);
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  LinkConditionerConfig good;
  good.target_port = 9;
  LinkConditionerConfig config = good;
  config.listen_host = "0.0.0.0";
  EXPECT_NE(refused(config).find("not a loopback address"), std::string::npos);
  config = good;
  config.target_host = "10.1.2.3";
  EXPECT_NE(refused(config).find("not a loopback address"), std::string::npos);
  config.target_host = "::ffff:127.0.0.1";
  EXPECT_NE(refused(config).find("not a loopback address"), std::string::npos);
  config.target_host = "example.com";
  EXPECT_NE(refused(config).find("not an IP address"), std::string::npos);
  config = good;
  config.target_port = 0;
  EXPECT_NE(refused(config).find("target_port"), std::string::npos);
  config = good;
  config.max_held_bytes = 0;
  EXPECT_NE(refused(config).find("max_held_bytes"), std::string::npos);
  config = good;
  config.path.to_client.latency = -1ms;
  EXPECT_NE(refused(config).find("to_client.latency"), std::string::npos);
  config = good;
  config.path.to_server.jitter = -1us;
  EXPECT_NE(refused(config).find("to_server.jitter"), std::string::npos);
  config = good;
  config.path.to_server.bandwidth_bytes_per_second = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(refused(config).find("bandwidth"), std::string::npos);
  config = good;
  config.path.stalls.duration = 200ms;
  config.path.stalls.every = 200ms;
  EXPECT_NE(refused(config).find("stalls.every"), std::string::npos);
  config = good;
  config.path.stalls.duration = 200ms;
  config.path.stalls.per_second = 5.0;
  EXPECT_NE(refused(config).find("stalls.per_second"), std::string::npos);
  config = good;
  config.path.stalls.at = {-5ms};
  EXPECT_NE(refused(config).find("stalls.at"), std::string::npos);
  // Loopback in every spelling is fine.
  config = good;
  config.listen_host = "127.0.0.2";
  config.target_host = "localhost";
  EXPECT_EQ(refused(config), "accepted");

  LinkConditioner relay(good);
  PathConfig bad;
  bad.stalls.per_second = -1.0;
  EXPECT_THROW(relay.set_path(bad), std::invalid_argument);
}

}  // namespace
}  // namespace physics_testing
