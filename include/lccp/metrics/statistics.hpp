#pragma once
// Percentiles of per-frame figures (latencies, stage times): the one
// definition every report uses (the run summary, lccp profile, the ROS
// node's diagnostics, perf/).
#include <vector>

namespace lccp {

// The nearest-rank percentile: the smallest value with at least the fraction
// q (0..1) of the values at or below it (Hyndman and Fan 1996, definition 1).
// 0 for no values.
double percentile(std::vector<double> values, double q);

struct Percentiles {
  double p50 = 0, p95 = 0, p99 = 0, max = 0;
};

// p50, p95, p99 (nearest rank) and the largest value; all 0 for no values.
Percentiles percentiles(std::vector<double> values);

}  // namespace lccp
