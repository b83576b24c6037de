#pragma once
// Summaries of per-step times.
#include <span>

namespace bench {

// Milliseconds; NaN for an empty span.
double median_ms(std::span<const double> seconds);
double mean_ms(std::span<const double> seconds);

}  // namespace bench
