#include "lccp/core/lccp.hpp"

#include "lccp/core/adjacency.hpp"
#include "lccp/core/convexity.hpp"
#include "lccp/core/normals.hpp"
#include "lccp/core/segments.hpp"
#include "lccp/core/supervoxels.hpp"
#include "lccp/core/voxel_grid.hpp"
#include "parallel.hpp"

namespace lccp {
namespace {

Labels label_points(const VoxelGrid& grid, const Supervoxels& supervoxels,
                    const std::vector<std::uint32_t>& segment_of_supervoxel) {
  Labels labels(grid.voxel_of_point.size(), 0);
  detail::parallel_for_each_index(labels.size(), [&](std::size_t i) {
    const std::uint32_t v = grid.voxel_of_point[i];
    if (v != kNoVoxel) labels[i] = segment_of_supervoxel[supervoxels.supervoxel_of_voxel[v]];
  });
  return labels;
}

// Adds the points i for which left_out(i) holds to w.skip.
template <typename Predicate>
void leave_out_points(SegmentationWork& w, Predicate&& left_out) {
  if (w.skip.empty()) w.skip.assign(w.cloud.size(), 0);
  detail::parallel_for_each_index(w.skip.size(), [&](std::size_t i) { w.skip[i] |= left_out(i) ? 1 : 0; });
}

// Points outside the region of interest are left out of everything that follows.
void keep_region(SegmentationWork& w, const RegionConfig& region) {
  if (!region.bounded()) return;
  leave_out_points(w, [&](std::size_t i) {
    const Eigen::Vector3f& p = w.cloud.points[i];
    return !region.contains(p.x(), p.y(), p.z());
  });
}

// The support plane's points are left out of the segmentation (Sec. III.C).
void remove_support(SegmentationWork& w, const SupportPlaneConfig& config, const SensorConfig& sensor) {
  if (!config.enabled) return;
  w.support = find_support_plane(w.cloud, config, w.skip, sensor);
  if (!w.support) return;
  leave_out_points(w, [&](std::size_t i) { return w.support->on_plane[i] != 0; });
}

}  // namespace

LccpSegmenter::LccpSegmenter(const LccpConfig& config) : config_(config) { validate(config_); }

SegmentationResult LccpSegmenter::segment(const CloudView& cloud) const { return std::move(run(cloud).result); }

SegmentationWork LccpSegmenter::run(const CloudView& cloud) const {
  SegmentationWork work(cloud);
  segment(work);
  return work;
}

// The paper's method, one line per stage (Sec. II.B, Appendix A).
void LccpSegmenter::segment(SegmentationWork& w) const {
  leave_out(w);
  build_voxels(w);
  compute_normals(w);
  place_seeds(w);
  grow_patches(w);
  build_graph(w);
  classify_convexity(w);
  merge_convex(w);
  filter_small(w);
}

// Stage 0: what is not segmented, as the config asks: the points outside the
// region of interest, then the support plane's among the rest.
void LccpSegmenter::leave_out(SegmentationWork& w) const {
  const StageTimer timer(w.result.times, Stage::support);
  keep_region(w, config_.region);
  remove_support(w, config_.support, config_.sensor);
}

void LccpSegmenter::build_voxels(SegmentationWork& w) const {
  const StageTimer timer(w.result.times, Stage::voxelize);
  w.grid = voxelize(w.cloud, config_.voxels, config_.sensor, config_.limits, w.skip);
}

void LccpSegmenter::compute_normals(SegmentationWork& w) const {
  const StageTimer timer(w.result.times, Stage::normals);
  w.normals = estimate_voxel_normals(w.grid, config_.normals);
}

void LccpSegmenter::place_seeds(SegmentationWork& w) const {
  const StageTimer timer(w.result.times, Stage::seeds);
  w.seeds = select_seeds(w.grid, config_.supervoxels, config_.voxels.voxel_size_m);
}

void LccpSegmenter::grow_patches(SegmentationWork& w) const {
  const StageTimer timer(w.result.times, Stage::growth);
  w.supervoxels = grow_supervoxels(w.grid, w.normals, w.seeds, config_);
}

void LccpSegmenter::build_graph(SegmentationWork& w) const {
  const StageTimer timer(w.result.times, Stage::adjacency);
  w.edges = supervoxel_adjacency(w.grid, w.supervoxels);
}

void LccpSegmenter::classify_convexity(SegmentationWork& w) const {
  const StageTimer timer(w.result.times, Stage::classify);
  const bool camera_frame = config_.sensor.depth_steps && w.grid.binning == Binning::camera;
  const PatchSizes sizes{config_.voxels.voxel_size_m, config_.supervoxels.seed_size_m,
                         camera_frame ? config_.sensor.step_per_m2() : 0.0f};
  w.convex = classify_edges(w.edges, w.supervoxels.centroids, w.supervoxels.normals, config_.convexity, sizes);
}

void LccpSegmenter::merge_convex(SegmentationWork& w) const {
  const StageTimer timer(w.result.times, Stage::components);
  w.segment_of_supervoxel = convex_components(w.supervoxels.size(), w.edges, w.convex);
}

// Stage 8 (A.4): small segments merged, segments numbered 1..K by size, and
// every point labelled through its voxel's supervoxel.
void LccpSegmenter::filter_small(SegmentationWork& w) const {
  const StageTimer timer(w.result.times, Stage::filter);
  merge_small_segments(w.segment_of_supervoxel, w.edges, config_.filter.n_filter_supervoxels);
  w.result.segment_count = relabel_by_size(w.segment_of_supervoxel);
  w.result.labels = label_points(w.grid, w.supervoxels, w.segment_of_supervoxel);
  w.result.voxel_count = static_cast<std::uint32_t>(w.grid.size());
  w.result.supervoxel_count = static_cast<std::uint32_t>(w.supervoxels.size());
}

}  // namespace lccp
