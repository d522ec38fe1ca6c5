#pragma once
// Internal: a robust standard deviation, for the support plane's noise and the
// open table's flatness.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace lccp::detail {

// 1.4826 times the median of `values` (reordered): a Gaussian's standard
// deviation when they are its absolute deviations (the MAD; Rousseeuw and
// Croux, "Alternatives to the median absolute deviation", JASA 88, 1993).
inline float robust_sigma(std::vector<float>& values) {
  if (values.empty()) return 0.0f;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return 1.4826f * *middle;
}

}  // namespace lccp::detail
