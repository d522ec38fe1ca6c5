#include "lccp/core/lccp.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <tuple>

#include "lccp/core/adjacency.hpp"
#include "lccp/core/convexity.hpp"
#include "lccp/core/grouped.hpp"
#include "lccp/core/normals.hpp"
#include "lccp/core/segments.hpp"
#include "lccp/core/supervoxels.hpp"
#include "lccp/core/union_find.hpp"
#include "lccp/core/voxel_grid.hpp"
#include "open_table.hpp"
#include "parallel.hpp"

namespace lccp {
namespace {

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

// Per point: 1 if a point off the support's band lies in its cell or a
// neighbouring one of a grid of distance_m cells (the voxel grid's cells and
// 26-neighbourhood, in the config's binning).
std::vector<std::uint8_t> near_other_points(const SegmentationWork& w, const LccpConfig& config) {
  VoxelConfig cells = config.voxels;
  cells.voxel_size_m = config.support.distance_m;
  const VoxelGrid grid = voxelize(w.cloud, cells, config.sensor, config.limits, w.skip);
  const std::vector<std::uint8_t>& on_plane = w.support->on_plane;
  std::vector<std::uint8_t> holds_other(grid.size(), 0), near(grid.size(), 0);
  detail::parallel_for_each_index(grid.size(), [&](std::size_t v) {
    const auto off = [&](std::uint32_t i) { return on_plane[i] == 0; };
    holds_other[v] = std::any_of(grid.points.begin(v), grid.points.end(v), off) ? 1 : 0;
  });
  detail::parallel_for_each_index(grid.size(), [&](std::size_t v) {
    const auto holds = [&](std::uint32_t u) { return holds_other[u] != 0; };
    near[v] = holds_other[v] || std::any_of(grid.neighbors.begin(v), grid.neighbors.end(v), holds) ? 1 : 0;
  });
  std::vector<std::uint8_t> out(w.cloud.size(), 0);
  detail::parallel_for_each_index(out.size(), [&](std::size_t i) {
    const std::uint32_t v = grid.voxel_of_point[i];
    out[i] = v != kNoVoxel ? near[v] : 0;
  });
  return out;
}

// The support plane's points are left out of the segmentation (Sec. III.C);
// with decided_by_patches only those away from any other point
// (SupportPlaneConfig), the others are left to settle_support.
void remove_support(SegmentationWork& w, const LccpConfig& config) {
  if (!config.support.enabled) return;
  w.support = find_support_plane(w.cloud, config.support, w.skip, config.sensor);
  if (!w.support) return;
  const std::vector<std::uint8_t>& on_plane = w.support->on_plane;
  if (!config.support.decided_by_patches) return leave_out_points(w, [&](std::size_t i) { return on_plane[i] != 0; });
  const std::vector<std::uint8_t> near = near_other_points(w, config);
  leave_out_points(w, [&](std::size_t i) { return on_plane[i] != 0 && near[i] == 0; });
}

// The supervoxel of point i (kNoVoxel: none).
std::uint32_t supervoxel_of_point(const SegmentationWork& w, std::size_t i) {
  const std::uint32_t v = w.grid.voxel_of_point[i];
  return v == kNoVoxel ? kNoVoxel : w.supervoxels.supervoxel_of_voxel[v];
}

// How far from a plane a mean at depth z may lie and be the plane's: half a
// depth step (the sensor rounds each depth to a step, q z^2: SensorConfig)
// plus three times the mean's spread (its standard error, and any more).
float centring_tolerance(float z, float spread_m, float step_per_m2) {
  return 0.5f * step_per_m2 * z * z + 3.0f * spread_m;
}

// The standard error of a mean of n samples with the support plane's noise.
float standard_error(const SegmentationWork& w, double n) {
  return static_cast<float>(w.support->noise_m / std::sqrt(n));
}

// Per supervoxel: its points, and its band points' heights above the
// support's plane and their depths, summed.
struct BandPatch {
  std::uint32_t points = 0;
  detail::HeightSum band;
  double depth = 0;
  bool banded() const { return 2 * band.points > points; }  // most of its points on the band
};

std::vector<BandPatch> band_patches(const SegmentationWork& w) {
  std::vector<BandPatch> patches(w.supervoxels.size());
  for (std::size_t i = 0; i < w.support->on_plane.size(); ++i) {
    const std::uint32_t s = supervoxel_of_point(w, i);
    if (s == kNoVoxel) continue;
    patches[s].points += 1;
    if (!w.support->on_plane[i]) continue;
    const Eigen::Vector3f& p = w.cloud.points[i];
    patches[s].band.add(w.support->plane.distance(p)), patches[s].depth += p.z();
  }
  return patches;
}

// A band region (banded supervoxels joined by edges): its band points, their
// depths, and the open table's points in the cells around its supervoxels.
struct BandRegion {
  detail::HeightSum band, open;
  double depth = 0;
};

// Per supervoxel, its band region (kNoVoxel if not banded); and each region's sums.
std::vector<BandRegion> band_regions(const SegmentationWork& w, const std::vector<BandPatch>& patches,
                                     const detail::OpenTable& open, std::vector<std::uint32_t>& region_of) {
  const auto n = static_cast<std::uint32_t>(patches.size());
  ConcurrentUnionFind sets(n);
  for (const Edge& e : w.edges) {
    if (patches[e.a].banded() && patches[e.b].banded()) sets.unite(e.a, e.b);
  }
  region_of.assign(n, kNoVoxel);
  for (std::uint32_t s = 0; s < n; ++s) region_of[s] = patches[s].banded() ? sets.find(s) : kNoVoxel;
  const Grouped<std::uint32_t> members = group_by_key<std::uint32_t>(n, [&](auto emit) {
    for (std::uint32_t s = 0; s < n; ++s) {
      if (region_of[s] != kNoVoxel) emit(region_of[s], s);
    }
  });
  std::vector<BandRegion> regions(n);
  std::vector<std::uint32_t> counted(open.size(), kNoVoxel);  // per cell: the last region that counted it
  std::vector<long> near;
  for (std::uint32_t r = 0; r < n; ++r) {
    for (const std::uint32_t s : members[r]) {
      regions[r].band.add(patches[s].band), regions[r].depth += patches[s].depth;
      const long cell = open.cell_of(w.supervoxels.centroids[s]);
      if (cell < 0) continue;
      open.around(cell, near);
      for (const long c : near) {
        std::uint32_t& last = counted[static_cast<std::size_t>(c)];
        if (last != r) last = r, regions[r].open.add(open.at(c));
      }
    }
  }
  return regions;
}

// Whether a band region is the support: its band points' mean height agrees
// with that of the open table around it (with none around, with the plane's)
// within the centring tolerance of the difference: its standard error and
// the open table's flatness. A region that does not is a plane of its own just
// above the support, inside the band of a noisy sensor (a pan's floor 5 mm up).
bool on_support(const SegmentationWork& w, const BandRegion& r, float flatness_m, float step_per_m2) {
  const double mean = r.band.height / r.band.points;
  const double reference = r.open.points > 0 ? r.open.height / r.open.points : 0.0;
  const float error = standard_error(w, r.band.points);
  const float open_error = r.open.points > 0 ? standard_error(w, r.open.points) : 0.0f;
  const float spread = std::sqrt(error * error + open_error * open_error + flatness_m * flatness_m);
  return std::abs(mean - reference) <= centring_tolerance(float(r.depth / r.band.points), spread, step_per_m2);
}

// The open table: the band points left out (on the band, skipped), in cells
// two seed spacings wide.
detail::OpenTable open_table(const SegmentationWork& w, const LccpConfig& config) {
  std::vector<std::uint8_t> left_out(w.support->on_plane.size());
  for (std::size_t i = 0; i < left_out.size(); ++i) left_out[i] = w.support->on_plane[i] && w.skip[i];
  return detail::OpenTable(w.cloud, left_out, w.support->plane, 2.0f * config.supervoxels.seed_size_m);
}

// The support's supervoxels: the band regions on_support, against the open table.
std::vector<std::uint8_t> support_patches(const SegmentationWork& w, const detail::OpenTable& open,
                                          const LccpConfig& config) {
  const float flatness = open.flatness_m(), q = config.sensor.step_per_m2();
  const std::vector<BandPatch> patches = band_patches(w);
  std::vector<std::uint32_t> region_of;
  const std::vector<BandRegion> regions = band_regions(w, patches, open, region_of);
  std::vector<std::uint8_t> support(patches.size(), 0);
  for (std::size_t s = 0; s < support.size(); ++s) {
    support[s] = region_of[s] != kNoVoxel && on_support(w, regions[region_of[s]], flatness, q);
  }
  return support;
}

// The distance from p to the plane of supervoxel `patch` (its centroid and normal).
float to_patch_plane(const Supervoxels& supervoxels, std::uint32_t patch, const Eigen::Vector3f& p) {
  return std::abs(supervoxels.normals[patch].dot(p - supervoxels.centroids[patch]));
}

// The support's height above its plane at p: the mean height of the open
// table's points in p's cell and those around it (the plane's, 0, where there
// are none). A table is flat only to within OpenTable::flatness_m from cell to
// cell, and its plane is fitted over all of it.
float support_height_at(const detail::OpenTable& open, const Eigen::Vector3f& p) {
  const long cell = open.cell_of(p);
  const detail::HeightSum near = cell < 0 ? detail::HeightSum{} : open.sum_around(cell);
  return near.points > 0 ? static_cast<float>(near.height / near.points) : 0.0f;
}

// A point on the band in a supervoxel that is not the support's: the support's
// if the support, where it is (support_height_at), fits it at least as well
// as its supervoxel's plane.
bool fits_support(const SegmentationWork& w, const detail::OpenTable& open, std::size_t i) {
  const std::uint32_t s = supervoxel_of_point(w, i);
  if (s == kNoVoxel) return true;  // left out: the open table
  const Eigen::Vector3f& p = w.cloud.points[i];
  const float to_support = std::abs(w.support->plane.distance(p) - support_height_at(open, p));
  return to_support <= to_patch_plane(w.supervoxels, s, p);
}

// decided_by_patches (SupportPlaneConfig), after the components: the
// support's supervoxels (support_patches) are the support's (kNoSegment), and
// so are their points within distance_m of the plane (the others are no
// segment's: label 0); a band point elsewhere is the support's if the support
// where it is fits it as well as its patch (fits_support).
void settle_support(SegmentationWork& w, const LccpConfig& config) {
  if (!w.support || !config.support.decided_by_patches) return;
  std::vector<std::uint8_t>& on_plane = w.support->on_plane;
  std::vector<std::uint32_t>& segment = w.segment_of_supervoxel;
  const detail::OpenTable open = open_table(w, config);
  const std::vector<std::uint8_t> support = support_patches(w, open, config);
  for (std::size_t s = 0; s < segment.size(); ++s) segment[s] = support[s] ? kNoSegment : segment[s];
  detail::parallel_for_each_index(on_plane.size(), [&](std::size_t i) {
    const std::uint32_t s = supervoxel_of_point(w, i);
    if (s != kNoVoxel && support[s]) {
      on_plane[i] = std::abs(w.support->plane.distance(w.cloud.points[i])) <= config.support.distance_m;
    } else {
      on_plane[i] = on_plane[i] && fits_support(w, open, i);
    }
  });
  w.support->inliers = static_cast<std::uint64_t>(std::count(on_plane.begin(), on_plane.end(), 1));
}

// Whether supervoxel a rests on supervoxel b: b faces up (its normal within
// upward_max_tilt_deg of the support's) and a's centroid lies above b's plane
// by more than the centring tolerance of a mean of a's voxel centroids (each
// a mean of one or more points: the tolerance errs wide).
bool rests_on(const SegmentationWork& w, std::uint32_t a, std::uint32_t b, float cos_upward, float step_per_m2) {
  const Supervoxels& sv = w.supervoxels;
  const Eigen::Vector3f& n = sv.normals[b];
  if (n.dot(w.support->plane.normal) < cos_upward) return false;
  const float tolerance = centring_tolerance(sv.centroids[a].z(), standard_error(w, sv.voxel_counts[a]), step_per_m2);
  return n.dot(sv.centroids[a] - sv.centroids[b]) > tolerance;
}

// Per edge, which side rests on the other's upward face (kARestsOnB,
// kBRestsOnA). The objects GroupingConfig builds from the parts rest on each
// other, and A.4 assumes a small segment is noise on the surface it joins: one
// standing on a face is not on it, so the filter first tries its other
// neighbours (a box's side, seen edge on in slivers, standing on a lower box:
// the sliver meets the upper box's front beside it). Empty without a support
// plane or grouping.
std::vector<std::uint8_t> resting_edges(const SegmentationWork& w, const std::vector<Edge>& edges,
                                        const LccpConfig& config) {
  if (!w.support || !config.grouping.objects_from_parts) return {};
  const auto cos_upward = static_cast<float>(config.grouping.cos_upward());
  const float q = config.sensor.step_per_m2();
  std::vector<std::uint8_t> resting(edges.size(), 0);
  detail::parallel_for_each_index(resting.size(), [&](std::size_t e) {
    const Edge& edge = edges[e];
    resting[e] = rests_on(w, edge.a, edge.b, cos_upward, q)   ? kARestsOnB
                 : rests_on(w, edge.b, edge.a, cos_upward, q) ? kBRestsOnA
                                                              : 0;
  });
  return resting;
}

// Per segment (component id): its supervoxels, and whether it has a
// neighbour it does not rest on.
struct SegmentReach {
  std::vector<std::uint32_t> size;
  std::vector<std::uint8_t> free;
};

SegmentReach segment_reach(const SegmentationWork& w, const std::vector<std::uint8_t>& resting) {
  const std::vector<std::uint32_t>& segment = w.segment_of_supervoxel;
  SegmentReach r{std::vector<std::uint32_t>(segment.size(), 0), std::vector<std::uint8_t>(segment.size(), 0)};
  for (const std::uint32_t g : segment) {
    if (g != kNoSegment) r.size[g] += 1;
  }
  for (std::size_t e = 0; e < w.edges.size(); ++e) {
    const std::uint32_t a = segment[w.edges[e].a], b = segment[w.edges[e].b];
    if (a == b || a == kNoSegment || b == kNoSegment) continue;
    if (!(resting[e] & kARestsOnB)) r.free[a] = 1;
    if (!(resting[e] & kBRestsOnA)) r.free[b] = 1;
  }
  return r;
}

// The voxels of the small segments that rest on every neighbour they have
// (none without `resting`), ascending in x.
std::vector<std::uint32_t> stranded_voxels(const SegmentationWork& w, const std::vector<std::uint8_t>& resting,
                                           std::uint32_t n_filter) {
  if (resting.empty()) return {};
  const SegmentReach reach = segment_reach(w, resting);
  std::vector<std::uint32_t> stranded;
  for (std::uint32_t v = 0; v < w.grid.size(); ++v) {
    const std::uint32_t g = w.segment_of_supervoxel[w.supervoxels.supervoxel_of_voxel[v]];
    if (g != kNoSegment && reach.size[g] <= n_filter && !reach.free[g]) stranded.push_back(v);
  }
  const auto x = [&](std::uint32_t v) { return w.grid.centroids[v].x(); };
  std::sort(stranded.begin(), stranded.end(), [&](std::uint32_t a, std::uint32_t b) { return x(a) < x(b); });
  return stranded;
}

// Edges for the noise filter only, beyond the 26-neighbourhood: from each
// supervoxel of a small segment that rests on every neighbour it has, to the
// supervoxels of other segments with a voxel centroid within two voxel sizes
// of one of its own (those not already edges; sorted, unique). A face seen
// nearly edge on is sampled sparser than the voxels (its points lie a pixel's
// footprint / cos(incidence) apart: 10 mm at 1 m and 80 deg), so its slivers
// can miss the face they continue by a cell and touch only the face they
// stand on, which the filter would otherwise have to join.
std::vector<Edge> gap_edges(const SegmentationWork& w, const std::vector<std::uint8_t>& resting, std::uint32_t n_filter,
                            float voxel_m) {
  const std::vector<std::uint32_t> stranded = stranded_voxels(w, resting, n_filter);
  if (stranded.empty()) return {};
  const std::vector<std::uint32_t>& segment = w.segment_of_supervoxel;
  const std::vector<std::uint32_t>& supervoxel = w.supervoxels.supervoxel_of_voxel;
  const float reach = 2.0f * voxel_m;
  const auto x_below = [&](std::uint32_t v, float x) { return w.grid.centroids[v].x() < x; };
  std::vector<Edge> gaps;
  for (std::uint32_t u = 0; u < w.grid.size(); ++u) {
    const Eigen::Vector3f& p = w.grid.centroids[u];
    const std::uint32_t t = supervoxel[u];
    if (segment[t] == kNoSegment) continue;
    for (auto it = std::lower_bound(stranded.begin(), stranded.end(), p.x() - reach, x_below);
         it != stranded.end() && w.grid.centroids[*it].x() <= p.x() + reach; ++it) {
      const std::uint32_t s = supervoxel[*it];
      if (segment[s] != segment[t] && (w.grid.centroids[*it] - p).squaredNorm() <= reach * reach) {
        gaps.push_back(Edge{std::min(s, t), std::max(s, t)});
      }
    }
  }
  const auto before = [](const Edge& a, const Edge& b) { return std::tie(a.a, a.b) < std::tie(b.a, b.b); };
  std::sort(gaps.begin(), gaps.end(), before);
  std::vector<Edge> new_gaps;  // not already edges (both lists sorted, unique)
  std::set_difference(gaps.begin(), std::unique(gaps.begin(), gaps.end()), w.edges.begin(), w.edges.end(),
                      std::back_inserter(new_gaps), before);
  return new_gaps;
}

// The noise filter's graph: the supervoxel adjacency, then the gap edges, and
// what the filter ranks them by.
struct FilterGraph {
  std::vector<Edge> edges;
  EdgeRanks ranks;
};

FilterGraph filter_graph(const SegmentationWork& w, const LccpConfig& config) {
  FilterGraph g{w.edges, {{}, resting_edges(w, w.edges, config)}};
  const std::vector<Edge> gaps =
      gap_edges(w, g.ranks.resting, config.filter.n_filter_supervoxels, config.voxels.voxel_size_m);
  const std::vector<std::uint8_t> resting = resting_edges(w, gaps, config);
  g.edges.insert(g.edges.end(), gaps.begin(), gaps.end());
  g.ranks.resting.insert(g.ranks.resting.end(), resting.begin(), resting.end());
  if (config.filter.by_convexity) {
    g.ranks.convexity = edge_convexity(g.edges, w.supervoxels.centroids, w.supervoxels.normals);
  }
  return g;
}

// Voxel v's supervoxel, then those of other segments (not the support's)
// among its 26 neighbours, each once.
struct BorderingPatches {
  std::array<std::uint32_t, 27> patch{};
  std::uint32_t count = 0;
};

BorderingPatches bordering_patches(const SegmentationWork& w, std::size_t v) {
  const std::vector<std::uint32_t>& supervoxel = w.supervoxels.supervoxel_of_voxel;
  const std::vector<std::uint32_t>& segment = w.segment_of_supervoxel;
  BorderingPatches b;
  b.patch[b.count++] = supervoxel[v];
  for (const std::uint32_t* u = w.grid.neighbors.begin(v); u != w.grid.neighbors.end(v); ++u) {
    const std::uint32_t t = supervoxel[*u];
    if (segment[t] == 0 || segment[t] == segment[supervoxel[v]]) continue;
    const auto end = b.patch.begin() + b.count;
    if (std::find(b.patch.begin(), end, t) == end) b.patch[b.count++] = t;
  }
  return b;
}

// How far from its own patch's plane a point must lie to be off it: with a
// support plane, the centring tolerance of one sample (its depth step and the
// plane's noise); without one, nothing is known of the noise: 0.
float off_patch_m(const SegmentationWork& w, const Eigen::Vector3f& p, float step_per_m2) {
  return w.support ? centring_tolerance(p.z(), standard_error(w, 1), step_per_m2) : 0.0f;
}

// The segment point p lies on: that of the bordering patch whose plane is
// nearest it, if that plane is kClearFit times nearer than its own patch's
// and p is off its own patch's plane (FilterConfig::boundary_points_by_plane);
// its own patch's otherwise.
std::uint32_t segment_by_plane(const SegmentationWork& w, const BorderingPatches& b, const Eigen::Vector3f& p,
                               float step_per_m2) {
  std::uint32_t nearest = b.patch[1];
  float nearest_m = to_patch_plane(w.supervoxels, nearest, p);
  for (std::uint32_t k = 2; k < b.count; ++k) {
    const float d = to_patch_plane(w.supervoxels, b.patch[k], p);
    if (d < nearest_m) nearest_m = d, nearest = b.patch[k];
  }
  const float own_m = to_patch_plane(w.supervoxels, b.patch[0], p);
  const bool clearly = FilterConfig::kClearFit * nearest_m < own_m && own_m > off_patch_m(w, p, step_per_m2);
  return w.segment_of_supervoxel[clearly ? nearest : b.patch[0]];
}

// Per supervoxel: 1 if it is in a segment (not the support's) and adjacent to
// a supervoxel of another segment.
std::vector<std::uint8_t> on_segment_borders(const SegmentationWork& w) {
  const std::vector<std::uint32_t>& segment = w.segment_of_supervoxel;
  std::vector<std::uint8_t> border(segment.size(), 0);
  for (const Edge& e : w.edges) {
    if (segment[e.a] != segment[e.b]) border[e.a] = segment[e.a] != 0, border[e.b] = segment[e.b] != 0;
  }
  return border;
}

// Every point the label of its voxel's supervoxel; 0 for a point on the
// support. With by_plane, a point of a voxel that borders another segment's
// voxel by segment_by_plane.
Labels label_points(const SegmentationWork& w, bool by_plane, float step_per_m2) {
  Labels labels(w.grid.voxel_of_point.size(), 0);
  detail::parallel_for_each_index(labels.size(), [&](std::size_t i) {
    const std::uint32_t s = supervoxel_of_point(w, i);
    if (s != kNoVoxel && !(w.support && w.support->on_plane[i])) labels[i] = w.segment_of_supervoxel[s];
  });
  if (!by_plane) return labels;
  const std::vector<std::uint8_t> border = on_segment_borders(w);
  detail::parallel_for_each_index_balanced(w.grid.size(), [&](std::size_t v) {
    if (!border[w.supervoxels.supervoxel_of_voxel[v]]) return;
    const BorderingPatches b = bordering_patches(w, v);
    if (b.count == 1) return;
    for (const std::uint32_t* i = w.grid.points.begin(v); i != w.grid.points.end(v); ++i) {
      if (labels[*i] != 0) labels[*i] = segment_by_plane(w, b, w.cloud.points[*i], step_per_m2);
    }
  });
  return labels;
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
  remove_support(w, config_);
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
  settle_support(w, config_);
  const FilterGraph graph = filter_graph(w, config_);
  merge_small_segments(w.segment_of_supervoxel, graph.edges, config_.filter.n_filter_supervoxels, graph.ranks);
  w.result.segment_count = relabel_by_size(w.segment_of_supervoxel);
  w.result.labels = label_points(w, config_.filter.boundary_points_by_plane, config_.sensor.step_per_m2());
  w.result.voxel_count = static_cast<std::uint32_t>(w.grid.size());
  w.result.supervoxel_count = static_cast<std::uint32_t>(w.supervoxels.size());
}

}  // namespace lccp
