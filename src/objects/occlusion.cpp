// A surface an object in front hides the middle of is seen as two parts that
// do not touch (an occluded box left and right of a mug). Whether two parts
// continue each other behind the occluder is decided with the paper's own
// test, eq. (5) on their nearest patches, and with what the sensor saw along
// the segment between them (occlusion.hpp).
#include "occlusion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>

#include <Eigen/Geometry>

#include "lccp/core/convexity.hpp"
#include "lccp/core/grouped.hpp"

namespace lccp::detail {
namespace {

using Vec3 = Eigen::Vector3f;

// What the sensor saw first in one direction: the depth, and the part of
// that point (a label of work.result; 0: none, such as the support's).
struct Seen {
  float depth = 0;
  std::uint32_t part = 0;
};

// The nearest point seen per direction from the sensor: bins of `bin` in
// (x / z, y / z), over the cloud's finite points in front of it (z > 0).
class SeenDepth {
 public:
  SeenDepth(const CloudView& cloud, const Labels& parts, float bin) : bin_(bin) {
    float lo_u = kInf, lo_v = kInf, hi_u = -kInf, hi_v = -kInf;
    for (const Vec3& p : cloud.points) {
      if (!(p.z() > 0.0f) || !std::isfinite(p.x() + p.y())) continue;
      lo_u = std::min(lo_u, p.x() / p.z()), hi_u = std::max(hi_u, p.x() / p.z());
      lo_v = std::min(lo_v, p.y() / p.z()), hi_v = std::max(hi_v, p.y() / p.z());
    }
    if (!(lo_u <= hi_u)) return;
    lo_u_ = lo_u, lo_v_ = lo_v;
    columns_ = static_cast<long>((hi_u - lo_u) / bin_) + 1, rows_ = static_cast<long>((hi_v - lo_v) / bin_) + 1;
    nearest_.assign(static_cast<std::size_t>(columns_ * rows_), Seen{kInf, 0});
    for (std::size_t i = 0; i < cloud.points.size(); ++i) {
      const Vec3& p = cloud.points[i];
      if (!(p.z() > 0.0f) || !std::isfinite(p.x() + p.y())) continue;
      Seen& seen = nearest_[static_cast<std::size_t>(index(p))];
      if (p.z() < seen.depth) seen = {p.z(), parts[i]};
    }
  }

  // The nearest point seen in x's direction; empty where nothing was seen.
  std::optional<Seen> at(const Vec3& x) const {
    const long i = x.z() > 0.0f ? index(x) : -1;
    if (i < 0 || !std::isfinite(nearest_[static_cast<std::size_t>(i)].depth)) return std::nullopt;
    return nearest_[static_cast<std::size_t>(i)];
  }

 private:
  static constexpr float kInf = std::numeric_limits<float>::infinity();
  long index(const Vec3& p) const {
    const long c = static_cast<long>(std::floor((p.x() / p.z() - lo_u_) / bin_));
    const long r = static_cast<long>(std::floor((p.y() / p.z() - lo_v_) / bin_));
    return c < 0 || r < 0 || c >= columns_ || r >= rows_ ? -1 : r * columns_ + c;
  }

  float bin_, lo_u_ = 0, lo_v_ = 0;
  long columns_ = 0, rows_ = 0;
  std::vector<Seen> nearest_;
};

// Whether the sensor cannot see the segment from a (on part p) to b (on part
// q) for a third object: no sample on it is seen past or falls on a point of
// no part (the support's: the gap is the table), none lies behind p or
// q themselves (they are then at different depths, one behind the other),
// at least half are hidden by (or meet) another part, and at most half fall
// where nothing was seen (the projector's shadow beside an occluder).
bool hidden_segment(const SeenDepth& seen, const Vec3& a, const Vec3& b, std::uint32_t p, std::uint32_t q,
                    const LccpConfig& config) {
  const float step = config.voxels.voxel_size_m;
  const int samples = std::max(2, static_cast<int>((b - a).norm() / step));
  int hidden = 0, empty = 0;
  for (int k = 1; k < samples; ++k) {
    const Vec3 x = a + (b - a) * (static_cast<float>(k) / static_cast<float>(samples));
    const float margin = config.sensor.depth_tolerance_m(x.z()) + step;
    const std::optional<Seen> first = seen.at(x);
    if (!first) {
      ++empty;
      continue;
    }
    const bool own = first->part == p || first->part == q;
    if (first->part == 0 || first->depth > x.z() + margin || (own && first->depth < x.z() - margin)) return false;
    hidden += !own;
  }
  return 2 * hidden >= samples - 1 && 2 * empty <= samples - 1;
}

// One plane continues from patch a to patch b: their normals within
// beta_thresh (the paper's bias for what counts as flat, eq. (1)) and their
// offset along them within the sensor's depth tolerance. Not a plane that
// faces up (within upward_max_tilt_deg of `up`, the support's normal): the
// tops of things of one height on one table are such a plane by coincidence.
bool continues(const Patch& a, const Patch& b, const LccpConfig& config, const Vec3& up) {
  if (normal_angle_deg(a, b) > config.convexity.beta_thresh_deg) return false;
  const float cos_upward = std::cos(config.grouping.upward_max_tilt_deg * std::numbers::pi_v<float> / 180.0f);
  if (a.normal.dot(up) >= cos_upward) return false;
  const float slack = config.sensor.depth_tolerance_m(0.5f * (a.centroid.z() + b.centroid.z()));
  return step_distance_m(a, b) <= slack;
}

// Per part its supervoxels.
Grouped<std::uint32_t> supervoxels_of_parts(const SegmentationWork& w) {
  return group_by_key<std::uint32_t>(w.result.segment_count, [&](auto emit) {
    for (std::uint32_t s = 0; s < w.segment_of_supervoxel.size(); ++s) {
      if (w.segment_of_supervoxel[s] != 0) emit(w.segment_of_supervoxel[s] - 1, s);
    }
  });
}

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// The pairs of supervoxels (one of each part) across the gap between two
// parts: within two seed spacings of the nearest pair, itself within max_gap
// (the facing patches: where a box shows two faces on either side of an
// occluder, the nearest pair may join a top to a front). Into `pairs`,
// cleared first: one buffer serves every pair of parts.
void facing_pairs(const SegmentationWork& w, std::span<const std::uint32_t> a, std::span<const std::uint32_t> b,
                  const LccpConfig& config, Pairs& pairs) {
  const auto distance = [&](std::uint32_t i, std::uint32_t j) {
    return (w.supervoxels.centroids[i] - w.supervoxels.centroids[j]).norm();
  };
  float nearest = std::numeric_limits<float>::infinity();
  for (const std::uint32_t i : a) {
    for (const std::uint32_t j : b) nearest = std::min(nearest, distance(i, j));
  }
  pairs.clear();
  if (!(nearest <= config.grouping.occluded_gap_m)) return;
  const float reach = nearest + 2.0f * config.supervoxels.seed_size_m;
  for (const std::uint32_t i : a) {
    for (const std::uint32_t j : b) {
      if (distance(i, j) <= reach) pairs.emplace_back(i, j);
    }
  }
}

// Whether parts p and q (labels) continue each other behind a third object
// across one of their facing pairs.
bool continue_hidden(const SegmentationWork& w, const SeenDepth& seen, const LccpConfig& config,
                     const Pairs& facing, std::uint32_t p, std::uint32_t q) {
  const Vec3 up = w.support ? w.support->plane.normal : Vec3::Zero();
  for (const auto& [i, j] : facing) {
    const Patch a{w.supervoxels.centroids[i], w.supervoxels.normals[i]};
    const Patch b{w.supervoxels.centroids[j], w.supervoxels.normals[j]};
    if (continues(a, b, config, up) && hidden_segment(seen, a.centroid, b.centroid, p, q, config)) return true;
  }
  return false;
}

}  // namespace

std::vector<std::pair<std::uint32_t, std::uint32_t>> hidden_continuations(
    const SegmentationWork& w, const LccpConfig& config, const std::vector<std::uint8_t>& eligible,
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& adjacent) {
  const SeenDepth seen(w.cloud, w.result.labels, config.voxels.voxel_size_m);
  const Grouped<std::uint32_t> members = supervoxels_of_parts(w);
  Pairs facing;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::uint32_t p = 0; p < members.size(); ++p) {
    for (std::uint32_t q = p + 1; q < members.size() && eligible[p]; ++q) {
      if (!eligible[q] || std::binary_search(adjacent.begin(), adjacent.end(), std::pair{p, q})) continue;
      facing_pairs(w, members[p], members[q], config, facing);
      if (continue_hidden(w, seen, config, facing, p + 1, q + 1)) pairs.emplace_back(p, q);
    }
  }
  return pairs;
}

}  // namespace lccp::detail
