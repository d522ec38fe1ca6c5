#pragma once
// The whole method on one cloud: the pipeline reads like the paper, one call per stage.
#include <cstdint>

#include "lccp/cloud.hpp"
#include "lccp/config.hpp"
#include "lccp/core/supervoxels.hpp"
#include "lccp/core/voxel_grid.hpp"

namespace lccp {

struct StageTimes {
  double voxelize_ms = 0;
  double normals_ms = 0;
  double seeds_ms = 0;
  double growth_ms = 0;
  double adjacency_ms = 0;
  double classify_ms = 0;
  double label_ms = 0;   // convex components
  double filter_ms = 0;  // noise filter, relabelling and per-point labels
  double total_ms() const {
    return voxelize_ms + normals_ms + seeds_ms + growth_ms + adjacency_ms + classify_ms + label_ms + filter_ms;
  }
};

struct SegmentationResult {
  Labels labels;  // per point: 1..segment_count, 0 for non-finite points
  std::uint32_t voxel_count = 0;
  std::uint32_t supervoxel_count = 0;
  std::uint32_t segment_count = 0;
  StageTimes times;
};

// Intermediate results between the stage groups (the streaming pipeline runs
// each group in its own flow-graph node).
struct VoxelizedCloud {
  VoxelGrid grid;
  std::vector<Eigen::Vector3f> normals;  // per voxel
};

struct GrownSupervoxels {
  VoxelizedCloud voxels;
  Supervoxels supervoxels;
};

class LccpSegmenter {
 public:
  // Throws lccp::Error if the config is out of range.
  explicit LccpSegmenter(const LccpConfig& config);

  // Labels every finite point; deterministic for a given cloud and config,
  // whatever the thread count. Throws lccp::Error for a cloud without finite points.
  SegmentationResult segment(const PointCloud& cloud) const;

  // segment() as three steps, for pipelining: stages 1-2, 3-4, 5-8. Each adds
  // its stage times to `times`. label() returns the same result as segment().
  VoxelizedCloud voxelize_with_normals(const PointCloud& cloud, StageTimes& times) const;
  GrownSupervoxels grow(VoxelizedCloud voxels, StageTimes& times) const;
  SegmentationResult label(const GrownSupervoxels& grown, const StageTimes& times) const;

  const LccpConfig& config() const { return config_; }

 private:
  LccpConfig config_;
};

}  // namespace lccp
