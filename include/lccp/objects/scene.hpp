#pragma once
// The paper's robot application (Sec. III.C, Fig. 5) on one frame: the support
// plane removed (stage 0), objects segmented (stages 1-8, Fig. 5 B), each object
// partitioned into parts (stage 9, Fig. 5 C), the geometry of every object and
// part (stage 10), and ids matched to the previous frame's (stage 11). With a
// one-level config the segments are the objects and stage 9 does nothing; with
// objects_from_parts (GroupingConfig) stages 1-8 find the parts and stage 9
// groups them into objects.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "lccp/cloud.hpp"
#include "lccp/config.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/stages.hpp"
#include "lccp/objects/geometry.hpp"
#include "lccp/objects/tracking.hpp"

namespace lccp {

struct ObjectSegments {
  SegmentGeometry object;
  std::vector<SegmentGeometry> parts;  // empty with one level
};

// Ids: the support segment has id 1 when the config removes a support plane;
// objects and parts share the ids after it, stable from frame to frame in a
// stream (a single cloud gets them in label order: objects by size, then parts).
struct SceneSegmentation {
  Labels labels;   // per point: the id of its part (of its object with one level), the support's, or 0
  Labels objects;  // per point: the id of its object, the support's, or 0; empty with one level
  std::optional<Plane> support_plane;
  std::uint32_t support_id = 0;       // 0: no support plane removed
  float support_noise_m = 0;          // the support plane's noise (SupportPlane::noise_m)
  std::vector<ObjectSegments> segments;  // objects in the first level's order (largest first)
  std::vector<std::uint32_t> new_ids;    // first seen in this frame, ascending
  std::vector<std::uint32_t> gone_ids;   // in the previous frame, not in this one, ascending
  std::uint32_t voxel_count = 0;         // the first level's
  std::uint32_t supervoxel_count = 0;    // the first level's
  std::uint32_t object_count = 0;
  std::uint32_t segment_count = 0;       // segments of the finest level (parts, or objects)
  StageTimes times;
};

// The part level of one object: its points as a cloud of their own, segmented.
struct ObjectParts {
  explicit ObjectParts(PointCloud points) : cloud(std::move(points)), work(cloud) {}
  PointCloud cloud;                   // the object's points
  std::vector<std::uint32_t> indices; // their indices in the frame's cloud
  SegmentationWork work;              // over `cloud`
};

// The parts of a config that groups objects from parts (GroupingConfig): the
// first level's segments, renumbered object by object (object k's parts are
// offsets[k - 1] + 1 .. offsets[k]), per point and per supervoxel; 0: none.
struct GroupedParts {
  Labels labels;
  std::vector<std::uint32_t> supervoxels;
  std::vector<std::uint32_t> offsets;  // objects + 1 entries, offsets[0] = 0
};

// One frame on its way through the stages of kStages. Every stage adds its
// time to objects.result.times (the frame's one record of stage times).
struct SceneWork {
  explicit SceneWork(const CloudView& cloud) : objects(cloud) {}

  SegmentationWork objects;                          // stages 0-8
  std::vector<std::unique_ptr<ObjectParts>> parts;   // stage 9: one per object (objects, then parts)
  std::optional<GroupedParts> grouped;               // stage 9 (objects from parts): `objects` then holds the objects
  std::vector<ObjectSegments> segments;              // stage 10, by dense labels
  SceneSegmentation result;                          // stage 11 (labels, ids)

  // The result with every stage's time; the work is spent.
  SceneSegmentation take_result() {
    result.times = objects.result.times;
    return std::move(result);
  }
};

// Immutable after construction: segment() and run_stage() may run on several
// threads at once, each on its own cloud or work (the pipeline does).
class SceneSegmenter {
 public:
  // Throws lccp::Error if the config is out of range.
  explicit SceneSegmenter(const SceneConfig& config);

  // Segments one cloud (read in place, not copied); ids in label order.
  // Deterministic, whatever the thread count. Throws lccp::Error for a cloud
  // without finite points or beyond the config's limits.
  SceneSegmentation segment(const CloudView& cloud) const;

  // Runs one stage before the ids (support to geometry, kStages order) on
  // `work`: the streaming pipeline runs them frames in parallel. Throws
  // lccp::Error for Stage::ids, which needs the stream's tracker: assign_ids.
  void run_stage(Stage stage, SceneWork& work) const;

  // Stage 11: ids matched to the previous frame's by `tracker`, the stream's
  // (one frame at a time, in frame order); labels and geometry renamed to them.
  // Null: a frame on its own, ids as a new tracker's first frame gets them
  // (first_frame_ids), in label order.
  void assign_ids(SceneWork& work, SegmentTracker* tracker) const;

  // A tracker for a stream: ids after the support's.
  SegmentTracker new_tracker() const;

  const SceneConfig& config() const { return config_; }

 private:
  std::uint32_t first_id() const;  // a new tracker's first id: after the support's
  void partition_objects(SceneWork& work) const;
  void group_objects(SceneWork& work) const;
  void describe(SceneWork& work) const;

  SceneConfig config_;
  LccpSegmenter objects_;
};

}  // namespace lccp
