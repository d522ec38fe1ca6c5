#pragma once
// Stable ids across the frames of a stream: each frame's objects and parts are
// matched to the previous frame's, so the same physical object keeps its id
// while it stays in view.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lccp/cloud.hpp"

namespace lccp {

// One frame's segments at both levels, as dense per-point labels (0 = none).
struct FrameSegments {
  const std::vector<Eigen::Vector3f>* points = nullptr;  // metres
  const Labels* objects = nullptr;                       // per point: object 1..object_count
  std::uint32_t object_count = 0;
  const Labels* parts = nullptr;                          // per point: part 1..part_count; null: no part level
  std::uint32_t part_count = 0;
};

struct TrackedIds {
  std::vector<std::uint32_t> object_ids;  // [object - 1]: its stable id
  std::vector<std::uint32_t> part_ids;    // [part - 1]: its stable id
  std::vector<std::uint32_t> new_ids;     // ids first seen in this frame, ascending
  std::vector<std::uint32_t> gone_ids;    // ids of the previous frame not in this one, ascending
};

class SegmentTracker {
 public:
  // Ids are handed out from first_id up, never reused; objects and parts share
  // one id space.
  explicit SegmentTracker(std::uint32_t first_id = 1);

  // Matches this frame's segments to the previous frame's and returns their ids.
  // Call once per frame, in frame order.
  TrackedIds update(const FrameSegments& frame);
};

}  // namespace lccp
