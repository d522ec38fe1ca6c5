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
  StageTimes times;
  return label(grow(voxelize_with_normals(cloud, times), times), times);
}

VoxelizedCloud LccpSegmenter::voxelize_with_normals(const PointCloud& cloud, StageTimes& times) const {
  LapTimer timer;
  VoxelizedCloud out;
  out.grid = voxelize(cloud, config_.voxels, config_.limits);
  times.voxelize_ms = timer.lap();
  out.normals = estimate_voxel_normals(out.grid);
  times.normals_ms = timer.lap();
  return out;
}

GrownSupervoxels LccpSegmenter::grow(VoxelizedCloud voxels, StageTimes& times) const {
  LapTimer timer;
  const float v = config_.voxels.voxel_size_m;
  const std::vector<std::uint32_t> seeds = select_seeds(voxels.grid, config_.supervoxels, v);
  times.seeds_ms = timer.lap();
  Supervoxels supervoxels = grow_supervoxels(voxels.grid, voxels.normals, seeds, config_.supervoxels, v);
  times.growth_ms = timer.lap();
  return {std::move(voxels), std::move(supervoxels)};
}

SegmentationResult LccpSegmenter::label(const GrownSupervoxels& grown, const StageTimes& times) const {
  SegmentationResult result;
  result.times = times;
  StageTimes& t = result.times;
  LapTimer timer;
  const VoxelGrid& grid = grown.voxels.grid;
  const Supervoxels& supervoxels = grown.supervoxels;

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
