#include "timing.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <vector>

namespace bench {

double median_ms(std::span<const double> seconds) {
  if (seconds.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> sorted(seconds.begin(), seconds.end());
  const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), middle, sorted.end());
  double median = *middle;
  if (sorted.size() % 2 == 0) {
    median = (median + *std::max_element(sorted.begin(), middle)) / 2.0;
  }
  return median * 1e3;
}

double mean_ms(std::span<const double> seconds) {
  if (seconds.empty()) return std::numeric_limits<double>::quiet_NaN();
  return std::accumulate(seconds.begin(), seconds.end(), 0.0) /
         static_cast<double>(seconds.size()) * 1e3;
}

}  // namespace bench
