// The one percentile definition (lccp/metrics/statistics.hpp): nearest rank.
#include <vector>

#include <gtest/gtest.h>

#include "lccp/metrics/statistics.hpp"

namespace lccp {
namespace {

TEST(Percentile, NearestRankOfUnsortedValues) {
  const std::vector<double> values{7, 1, 9, 3, 5};  // sorted: 1 3 5 7 9
  EXPECT_EQ(percentile(values, 0.0), 1);   // rank clamped to 1
  EXPECT_EQ(percentile(values, 0.2), 1);   // ceil(1.0) = 1
  EXPECT_EQ(percentile(values, 0.5), 5);   // ceil(2.5) = 3
  EXPECT_EQ(percentile(values, 0.61), 7);  // ceil(3.05) = 4
  EXPECT_EQ(percentile(values, 1.0), 9);
  EXPECT_EQ(percentile({4, 2}, 0.5), 2);   // even count: the lower middle, a value of the set
  EXPECT_EQ(percentile({}, 0.5), 0);
}

TEST(Percentile, SummaryOfAHundredValues) {
  std::vector<double> values;
  for (int v = 100; v >= 1; --v) values.push_back(v);
  const Percentiles p = percentiles(values);
  EXPECT_EQ(p.p50, 50);
  EXPECT_EQ(p.p95, 95);
  EXPECT_EQ(p.p99, 99);
  EXPECT_EQ(p.max, 100);
  const Percentiles none = percentiles({});
  EXPECT_EQ(none.p50 + none.p95 + none.p99 + none.max, 0);
}

}  // namespace
}  // namespace lccp
