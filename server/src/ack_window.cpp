#include "ack_window.h"

#include <algorithm>
#include <cmath>

namespace server {

AckWindow::AckWindow(std::uint32_t floor, bool adapts, Sizing sizing)
    : floor_(std::max<std::uint32_t>(1, floor)), adapts_(adapts), sizing_(sizing) {}

void AckWindow::sent(std::uint64_t tick, time_point at) { sent_.push_back({tick, at}); }

void AckWindow::acked(std::uint64_t tick, time_point at) {
  std::optional<time_point> sent_at;
  while (!sent_.empty() && sent_.front().tick <= tick) {
    if (sent_.front().tick == tick) sent_at = sent_.front().at;
    sent_.pop_front();
  }
  if (sent_at && at >= *sent_at) {
    samples_.push_back({at, at - *sent_at});
    while (samples_.size() > kMaxSamples || (samples_.front().at + kRoundTripMemory < at)) {
      samples_.pop_front();
    }
    // Kept here, where the samples change, not in window(): that is asked for on
    // every due tick of every client.
    least_ =
        std::min_element(samples_.begin(), samples_.end(), [](const Sample& x, const Sample& y) {
          return x.round_trip < y.round_trip;
        })->round_trip;
  }
}

std::uint32_t AckWindow::window() const {
  const auto rtt = round_trip();
  if (!adapts_ || !rtt || sizing_.snapshot_period.count() <= 0) return floor_;
  // The snapshots of a round trip and a quarter more, plus four for the client's own
  // handling and the jitter the minimum leaves out.
  const double in_flight = 1.25 * static_cast<double>(rtt->count()) /
                           static_cast<double>(sizing_.snapshot_period.count());
  const double wanted = std::ceil(in_flight) + 4.0;
  const double cap = std::max<double>(floor_, sizing_.cap);
  return static_cast<std::uint32_t>(std::clamp(wanted, static_cast<double>(floor_), cap));
}

}  // namespace server
