#pragma once
// Stable ids across the frames of a stream: each frame's objects and parts are
// matched to the previous frame's, so the same physical object keeps its id
// while it stays in view.
#include <cstdint>
#include <memory>
#include <vector>

#include "lccp/cloud.hpp"
#include "lccp/core/occupied_cells.hpp"  // FrameSegments

namespace lccp {

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
  // Call once per frame, in frame order. Matching: by overlap (IoU) of the 1 cm
  // cells each segment occupies, greedily, best first; a part inherits only from
  // a part of the previous object its own object inherited from. An object that
  // merged into another (which holds at least a quarter of its cells) keeps its
  // id with the merged object for up to 30 frames: if it splits off again where
  // it was, it takes the id back (it is not in new_ids; gone_ids listed it when
  // it merged). New segments
  // get new ids in dense order, objects first, then parts (a tracker's first
  // frame: object k gets first_id + k - 1). Points whose object label is 0, or
  // that are not finite, are ignored. Throws lccp::Error if the labels do not
  // fit the frame (sizes, a label above its count) or the ids are used up.
  TrackedIds update(const FrameSegments& frame);

  ~SegmentTracker();
  SegmentTracker(SegmentTracker&&) noexcept;
  SegmentTracker& operator=(SegmentTracker&&) noexcept;

 private:
  struct History;  // the previous frame's cells and ids, and the absorbed ids (tracking.cpp)
  std::uint32_t next_id_;
  std::unique_ptr<History> history_;
};

// The ids a new SegmentTracker(first_id) gives `frame` in its first update
// (objects first_id.., then the parts; every id new, none gone), without the
// cells a next frame would be matched against: for a frame on its own (one
// cloud, a batch of files), where they would be thrown away. Throws
// lccp::Error as update does.
TrackedIds first_frame_ids(const FrameSegments& frame, std::uint32_t first_id);

}  // namespace lccp
