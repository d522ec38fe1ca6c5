#include "lccp/metrics/statistics.hpp"

#include <algorithm>
#include <cmath>

namespace lccp {
namespace {

// `sorted` ascending and not empty.
double nearest_rank(const std::vector<double>& sorted, double q) {
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

}  // namespace

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  return nearest_rank(values, q);
}

Percentiles percentiles(std::vector<double> values) {
  if (values.empty()) return {};
  std::sort(values.begin(), values.end());
  return {nearest_rank(values, 0.50), nearest_rank(values, 0.95), nearest_rank(values, 0.99), values.back()};
}

}  // namespace lccp
