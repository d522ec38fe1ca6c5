#pragma once
// The whole method on one cloud, stage by stage (lccp/stages.hpp).
#include <cstdint>

#include "lccp/cloud.hpp"
#include "lccp/config.hpp"
#include "lccp/core/adjacency.hpp"
#include "lccp/core/normals.hpp"
#include "lccp/stages.hpp"
#include "lccp/core/supervoxels.hpp"
#include "lccp/core/support_plane.hpp"
#include "lccp/core/voxel_grid.hpp"

namespace lccp {

struct SegmentationResult {
  Labels labels;  // per point: 1..segment_count, 0 for non-finite and skipped points
  std::uint32_t voxel_count = 0;
  std::uint32_t supervoxel_count = 0;
  std::uint32_t segment_count = 0;
  StageTimes times;
};

// One cloud on its way through the stages: each stage reads what the earlier
// ones left and adds its own result. The streaming pipeline hands it from node
// to node; the arrays `cloud` views must outlive it.
struct SegmentationWork {
  explicit SegmentationWork(CloudView points) : cloud(points) {}

  CloudView cloud;
  std::vector<std::uint8_t> skip;                      // per point, 1: left out (empty: none); set by the caller
  std::optional<SupportPlane> support;                 // support (its points join `skip`; by patches: some, and filter settles the rest)
  VoxelGrid grid;                                      // voxelize
  VoxelNormals normals;                                // normals, per voxel
  std::vector<std::uint32_t> seeds;                    // seeds, voxel indices
  Supervoxels supervoxels;                             // growth
  std::vector<Edge> edges;                             // adjacency
  std::vector<std::uint8_t> convex;                    // classify, per edge
  std::vector<std::uint32_t> segment_of_supervoxel;    // components, then filter
  SegmentationResult result;                           // filter (labels, counts); times from every stage
};

// The method's stages on one cloud as named steps, each reading what the
// earlier ones left in a SegmentationWork and timing itself (StageTimer into
// work.result.times). segment() runs them in the paper's order.
class LccpSegmenter {
 public:
  // Throws lccp::Error if the config is out of range.
  explicit LccpSegmenter(const LccpConfig& config);

  // Labels every finite point (but those outside the config's region of
  // interest and those on the support plane, if the config removes it: see
  // SegmentationWork::support); deterministic for a given cloud and config,
  // whatever the thread count. Throws lccp::Error for a cloud without finite
  // points; one whose finite points are all left out gives no segment (every
  // label 0), as an empty table does.
  SegmentationResult segment(const CloudView& cloud) const;

  // The same, keeping every stage's output (grid, normals, supervoxels, graph)
  // for what is computed from it (per-segment geometry).
  SegmentationWork run(const CloudView& cloud) const;

  // Stages 0-8 on `work`, one after the other.
  void segment(SegmentationWork& work) const;

  void leave_out(SegmentationWork& work) const;           // 0. region of interest, support plane (Sec. III.C)
  void build_voxels(SegmentationWork& work) const;        // 1. voxel grid, 26-adjacency (A.1)
  void compute_normals(SegmentationWork& work) const;     // 2. one normal per voxel
  void place_seeds(SegmentationWork& work) const;         // 3. seeds on a grid of R_seed
  void grow_patches(SegmentationWork& work) const;        // 4. supervoxels
  void build_graph(SegmentationWork& work) const;         // 5. supervoxel adjacency graph (A.1)
  void classify_convexity(SegmentationWork& work) const;  // 6. CC and SC, eq. (1)-(5) (A.2)
  void merge_convex(SegmentationWork& work) const;        // 7. components over convex edges (A.3)
  void filter_small(SegmentationWork& work) const;        // 8. small segments merged, a label per point (A.4)

  const LccpConfig& config() const { return config_; }

 private:
  LccpConfig config_;
};

}  // namespace lccp
