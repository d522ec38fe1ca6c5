#pragma once
// Stage 9 with GroupingConfig::objects_from_parts: objects as unions of the
// parts a single-level segmentation found, grouped by how each part rests on
// the support plane (config.hpp, GroupingConfig, states the rule).
#include <cstdint>
#include <vector>

#include "lccp/config.hpp"
#include "lccp/core/lccp.hpp"

namespace lccp {

// Per part label 1..P of work.result (index label - 1):
struct PartGroups {
  // its object, 1..K, numbered by decreasing points (ties: the object of the
  // smaller part label first), or 0 for a part that is no object: it lies
  // wholly within contact_m of the plane (a piece of the table the support's
  // band left) and joins no object. Its points are then unassigned, as a
  // dropped object's.
  std::vector<std::uint32_t> object;
  // the part label it is one part with: the smallest of the pieces with no
  // body of their own (neither standing nor resting on one) that meet within
  // one object (a handle the segmentation cut in two), itself otherwise.
  std::vector<std::uint32_t> part;
};

// Without a support plane in the work every part is an object of its own.
// Needs the work's supervoxels, edges and segment_of_supervoxel (stages 0-8
// run). Deterministic.
PartGroups group_parts(const SegmentationWork& work, const LccpConfig& config);

}  // namespace lccp
