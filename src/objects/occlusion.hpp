#pragma once
// One surface seen in pieces around a nearer object (grouping.cpp): which
// parts continue each other behind an occluder.
#include <cstdint>
#include <utility>
#include <vector>

#include "lccp/config.hpp"
#include "lccp/core/lccp.hpp"

namespace lccp::detail {

// Pairs of parts (0-based labels - 1, a < b) of work.result that are one
// surface seen on either side of a nearer object: parts `eligible` (per part)
// and not adjacent (`adjacent`: sorted pairs a < b), whose nearest supervoxels
// (at most config.grouping.occluded_gap_m apart) would be convexly and
// smoothly connected (eq. (1), (4); a step no larger than their angle explains
// over their distance, plus the sensor's depth tolerance), and whose
// connecting segment the sensor cannot see: along it every direction from the
// sensor (the origin) meets a nearer point or none, and at least one a nearer.
// A segment it sees past (the table or the wall behind a gap) is not hidden.
std::vector<std::pair<std::uint32_t, std::uint32_t>> hidden_continuations(
    const SegmentationWork& work, const LccpConfig& config, const std::vector<std::uint8_t>& eligible,
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& adjacent);

}  // namespace lccp::detail
