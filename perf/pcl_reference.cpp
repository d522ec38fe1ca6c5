#include "pcl_reference.hpp"

#include <chrono>
#include <map>
#include <string>

#include <pcl/console/print.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/segmentation/lccp_segmentation.h>
#include <pcl/segmentation/supervoxel_clustering.h>

#include "lccp/error.hpp"

namespace lccp::perf {
namespace {

using PclPoint = pcl::PointXYZRGBA;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Keeps width/height, so an organized cloud stays organized and PCL applies its
// single camera transform exactly as it does for its own organized input.
pcl::PointCloud<PclPoint>::Ptr to_pcl(const PointCloud& cloud) {
  auto out = pcl::make_shared<pcl::PointCloud<PclPoint>>();
  out->resize(cloud.size());
  if (cloud.organized() && static_cast<std::size_t>(cloud.width) * cloud.height == cloud.size()) {
    out->width = cloud.width;
    out->height = cloud.height;
  } else {
    out->width = static_cast<std::uint32_t>(cloud.size());
    out->height = 1;
  }
  bool dense = true;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    PclPoint& p = (*out)[i];
    p.getVector3fMap() = cloud.points[i];
    const std::uint32_t rgb = cloud.has_colors() ? cloud.colors[i] : 0u;
    p.rgba = 0xFF000000u | (rgb & 0x00FFFFFFu);
    dense = dense && is_finite(cloud.points[i]);
  }
  out->is_dense = dense;
  return out;
}

}  // namespace

void quiet_pcl_console() { pcl::console::setVerbosityLevel(pcl::console::L_ERROR); }

PclLccpResult run_pcl_lccp(const PointCloud& cloud, const LccpConfig& config) {
  std::size_t finite = 0;
  for (const auto& p : cloud.points) finite += is_finite(p) ? 1 : 0;
  if (finite == 0) throw Error("run_pcl_lccp: the cloud has no finite point");

  PclLccpResult result;
  const float voxel_m = config.voxels.voxel_size_m;
  const float seed_m = config.supervoxels.seed_size_m;

  auto start = Clock::now();
  const pcl::PointCloud<PclPoint>::ConstPtr input = to_pcl(cloud);
  result.convert_ms = ms_since(start);

  // Supervoxels (VCCS). No setUseSingleCameraTransform: PCL's default behaviour.
  start = Clock::now();
  pcl::SupervoxelClustering<PclPoint> supervoxels(voxel_m, seed_m);
  supervoxels.setInputCloud(input);
  supervoxels.setSpatialImportance(config.supervoxels.spatial_weight);
  supervoxels.setNormalImportance(config.supervoxels.normal_weight);
  supervoxels.setColorImportance(config.supervoxels.color_weight);
  std::map<std::uint32_t, pcl::Supervoxel<PclPoint>::Ptr> clusters;
  supervoxels.extract(clusters);
  std::multimap<std::uint32_t, std::uint32_t> adjacency;
  supervoxels.getSupervoxelAdjacency(adjacency);
  result.supervoxels_ms = ms_since(start);
  result.supervoxel_count = static_cast<std::uint32_t>(clusters.size());

  // LCCP as configured: CC, SC and PCL's smoothness check as in `config`; no k-convexity.
  start = Clock::now();
  pcl::LCCPSegmentation<PclPoint> lccp;
  lccp.setConcavityToleranceThreshold(config.convexity.beta_thresh_deg);
  lccp.setSanityCheck(config.convexity.sanity_criterion);
  lccp.setSmoothnessCheck(config.convexity.smoothness_check, voxel_m, seed_m, config.convexity.smoothness_threshold);
  lccp.setKFactor(0);
  lccp.setInputSupervoxels(clusters, adjacency);
  lccp.setMinSegmentSize(config.filter.n_filter_supervoxels);
  lccp.segment();
  result.lccp_ms = ms_since(start);

  // getLabeledCloud() is per INPUT point, input order (getLabeledVoxelCloud() would be
  // per voxel); non-finite points and voxels no supervoxel reached carry label 0, and
  // relabelCloud maps 0 to 0.
  start = Clock::now();
  const pcl::PointCloud<pcl::PointXYZL>::Ptr labelled = supervoxels.getLabeledCloud();
  lccp.relabelCloud(*labelled);
  if (labelled->size() != cloud.size())
    throw Error("run_pcl_lccp: PCL returned " + std::to_string(labelled->size()) + " labels for " +
                std::to_string(cloud.size()) + " points");
  result.labels.resize(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    result.labels[i] = is_finite(cloud.points[i]) ? (*labelled)[i].label : 0u;
  result.labels_ms = ms_since(start);

  std::map<std::uint32_t, std::set<std::uint32_t>> segments;
  lccp.getSegmentToSupervoxelMap(segments);
  result.segment_count = static_cast<std::uint32_t>(segments.size());
  result.voxel_count = static_cast<std::uint32_t>(supervoxels.getVoxelCentroidCloud()->size());
  return result;
}

}  // namespace lccp::perf
