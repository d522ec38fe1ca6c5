#pragma once
// Summary statistics of per-frame timings, shared by the perf/ programs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "lccp/metrics/statistics.hpp"

namespace lccp::perf {

inline double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The median as statistics defines it (the mean of the two middle values for an
// even count), as RESULTS.md quotes timings; reports' p50 is the nearest rank.
inline double median(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

inline double mean(const std::vector<double>& values) {
  if (values.empty()) return 0;
  double sum = 0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

// Percentiles: lccp::percentile (lccp/metrics/statistics.hpp), the library's one definition.

}  // namespace lccp::perf
