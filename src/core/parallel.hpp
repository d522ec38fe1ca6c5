#pragma once
// Internal: the parallel loop shapes the stages share.
#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

namespace lccp::detail {

// Calls body(range) over [0, n) in parallel, one contiguous share per thread:
// voxels and points that are neighbours in memory stay in one core's cache
// (perf/RESULTS.md: median growth 10.9 -> 9.9 ms on 2 threads against TBB's default split).
template <typename RangeBody>
void parallel_ranges(std::size_t n, RangeBody&& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), body, tbb::static_partitioner());
}

// Calls body(i) for every i in [0, n), as parallel_ranges does.
template <typename Body>
void parallel_for_each_index(std::size_t n, Body&& body) {
  parallel_ranges(n, [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) body(i);
  });
}

// Calls body(i) for every i in [0, n) in parallel, in ranges TBB splits and
// steals as threads run out: for loops whose work clusters in a few stretches
// of the indices, which one contiguous share per thread would leave on one
// thread (the seam-point pass: perf/RESULTS.md, 2 threads 1.19 -> 0.93 ms on office1).
template <typename Body>
void parallel_for_each_index_balanced(std::size_t n, Body&& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) body(i);
  });
}

}  // namespace lccp::detail
