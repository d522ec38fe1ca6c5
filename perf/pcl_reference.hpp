#pragma once
// PCL 1.13's own LCCP (pcl::SupervoxelClustering + pcl::LCCPSegmentation), run with
// the paper's setup, as the reference that perf/ compares LccpSegmenter against.
// Only perf/ and tests/ may include PCL; this header does not, so callers stay PCL-free.
#include <cstdint>

#include "lccp/cloud.hpp"
#include "lccp/config.hpp"

namespace lccp::perf {

struct PclLccpResult {
  Labels labels;  // one per input point, input order; 0 = PCL gave the point no label
  std::uint32_t voxel_count = 0;       // PCL's voxel centroid cloud size
  std::uint32_t supervoxel_count = 0;  // supervoxels extracted
  std::uint32_t segment_count = 0;     // LCCP segments after the size filter
  double convert_ms = 0;      // lccp::PointCloud -> pcl::PointCloud<PointXYZRGBA>
  double supervoxels_ms = 0;  // setInputCloud + extract + getSupervoxelAdjacency
  double lccp_ms = 0;         // setInputSupervoxels + segment
  double labels_ms = 0;       // getLabeledCloud + relabelCloud + copy to per-point labels
  double total_ms() const { return convert_ms + supervoxels_ms + lccp_ms + labels_ms; }
};

// Segments `cloud` with PCL using `config`: voxel_size_m, seed_size_m, the three
// importances, beta_thresh_deg, sanity_criterion, smoothness_check with its threshold
// and n_filter_supervoxels. PCL's own defaults are kept for everything else: single
// camera transform for organized clouds only, sanity thresholds (60 deg, 25 deg, 0.25)
// hard-coded in PCL, no supervoxel refinement, extended convexity off (k = 0).
// config.voxels.binning and the theta/beta_off/slope fields have no PCL setter and are
// ignored. Throws lccp::Error if the cloud has no finite point.
PclLccpResult run_pcl_lccp(const PointCloud& cloud, const LccpConfig& config);

// Silences PCL's console warnings (PCL_WARN) for the rest of the process.
void quiet_pcl_console();

}  // namespace lccp::perf
