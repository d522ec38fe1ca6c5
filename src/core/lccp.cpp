#include "lccp/core/lccp.hpp"

#include <chrono>

#include "lccp/core/adjacency.hpp"
#include "lccp/core/convexity.hpp"
#include "lccp/core/normals.hpp"
#include "lccp/core/segments.hpp"
#include "lccp/core/supervoxels.hpp"
#include "lccp/core/voxel_grid.hpp"
#include "parallel.hpp"

namespace lccp {
namespace {

// Milliseconds since the previous lap.
class LapTimer {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
    return ms;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

Labels label_points(const VoxelGrid& grid, const Supervoxels& supervoxels,
                    const std::vector<std::uint32_t>& segment_of_supervoxel) {
  Labels labels(grid.voxel_of_point.size(), 0);
  detail::parallel_for_each_index(labels.size(), [&](std::size_t i) {
    const std::uint32_t v = grid.voxel_of_point[i];
    if (v != kNoVoxel) labels[i] = segment_of_supervoxel[supervoxels.supervoxel_of_voxel[v]];
  });
  return labels;
}

}  // namespace

LccpSegmenter::LccpSegmenter(const LccpConfig& config) : config_(config) { validate(config_); }

SegmentationResult LccpSegmenter::segment(const PointCloud& cloud) const {
  SegmentationResult result;
  StageTimes& t = result.times;
  LapTimer timer;
  const float v = config_.voxels.voxel_size_m;

  const VoxelGrid grid = voxelize(cloud, config_.voxels);
  t.voxelize_ms = timer.lap();
  const std::vector<Eigen::Vector3f> normals = estimate_voxel_normals(grid);
  t.normals_ms = timer.lap();
  const std::vector<std::uint32_t> seeds = select_seeds(grid, config_.supervoxels, v);
  t.seeds_ms = timer.lap();
  const Supervoxels supervoxels = grow_supervoxels(grid, normals, seeds, config_.supervoxels, v);
  t.growth_ms = timer.lap();
  const std::vector<Edge> edges = supervoxel_adjacency(grid, supervoxels);
  t.adjacency_ms = timer.lap();
  const std::vector<std::uint8_t> convex =
      classify_edges(edges, supervoxels.centroids, supervoxels.normals, config_.convexity);
  t.classify_ms = timer.lap();
  std::vector<std::uint32_t> segments = convex_components(supervoxels.size(), edges, convex);
  t.label_ms = timer.lap();
  merge_small_segments(segments, edges, config_.filter.n_filter_supervoxels);
  result.segment_count = relabel_by_size(segments);
  result.labels = label_points(grid, supervoxels, segments);
  t.filter_ms = timer.lap();

  result.voxel_count = static_cast<std::uint32_t>(grid.size());
  result.supervoxel_count = static_cast<std::uint32_t>(supervoxels.size());
  return result;
}

}  // namespace lccp
