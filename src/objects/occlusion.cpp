// A surface an object in front hides the middle of is seen as two parts that
// do not touch (an occluded box left and right of a mug). Whether two parts
// continue each other behind the occluder is decided with the paper's own
// test, eq. (5) on their nearest patches, and with what the sensor saw along
// the segment between them (occlusion.hpp). A part that hangs in the air,
// touching nothing, is held by what the sensor does not see: the body it
// vanishes behind, if it comes close to it there (held_behind).
#include "occlusion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>

#include <Eigen/Geometry>

#include "convex_hull.hpp"
#include "lccp/core/convexity.hpp"
#include "lccp/core/grouped.hpp"

namespace lccp::detail {
namespace {

using Vec3 = Eigen::Vector3f;
using Vec2d = Eigen::Vector2d;

// floor(v) for a finite v within long's range, without a call into libm.
long floor_of(float v) {
  const auto t = static_cast<long>(v);
  return t - (v < static_cast<float>(t));
}

}  // namespace

// Two passes over the directions (x / z, y / z), each divided once: their
// bounds, then each point into its bin.
SeenDepth::SeenDepth(const CloudView& cloud, const Labels& parts, float bin) : bin_(bin) {
  const std::size_t n = cloud.size();
  std::vector<float> u(n), v(n);
  float lo_u = kInf, lo_v = kInf, hi_u = -kInf, hi_v = -kInf;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = cloud.points[i];
    const bool ahead = p.z() > 0.0f && std::isfinite(p.x() + p.y());
    u[i] = ahead ? p.x() / p.z() : kInf, v[i] = ahead ? p.y() / p.z() : kInf;
    if (!ahead) continue;
    lo_u = std::min(lo_u, u[i]), hi_u = std::max(hi_u, u[i]);
    lo_v = std::min(lo_v, v[i]), hi_v = std::max(hi_v, v[i]);
  }
  if (!(lo_u <= hi_u)) return;
  lo_u_ = lo_u, lo_v_ = lo_v;
  columns_ = static_cast<long>((hi_u - lo_u) / bin_) + 1, rows_ = static_cast<long>((hi_v - lo_v) / bin_) + 1;
  nearest_.assign(static_cast<std::size_t>(columns_ * rows_), Seen{kInf, 0});
  for (std::size_t i = 0; i < n; ++i) {
    if (u[i] == kInf) continue;
    const float z = cloud.points[i].z();
    const auto bin_index = static_cast<std::size_t>(static_cast<long>((v[i] - lo_v) / bin_) * columns_ +
                                                    static_cast<long>((u[i] - lo_u) / bin_));
    Seen& seen = nearest_[bin_index];
    if (z < seen.depth) seen = {z, parts[i]};
  }
}

std::optional<Seen> SeenDepth::at(const Vec3& x) const {
  const long i = x.z() > 0.0f ? index(x) : -1;
  if (i < 0 || !std::isfinite(nearest_[static_cast<std::size_t>(i)].depth)) return std::nullopt;
  return nearest_[static_cast<std::size_t>(i)];
}

long SeenDepth::index(const Vec3& p) const {
  const float u = (p.x() / p.z() - lo_u_) / bin_, v = (p.y() / p.z() - lo_v_) / bin_;
  if (!(std::abs(u) < 1e9f && std::abs(v) < 1e9f)) return -1;
  const long c = floor_of(u), r = floor_of(v);
  return c < 0 || r < 0 || c >= columns_ || r >= rows_ ? -1 : r * columns_ + c;
}

namespace {

// The samples of the segment from a to b, one per voxel size (at least one),
// ends excluded: visit(x) for each while it returns true. Whether all did.
template <class Visit>
bool every_sample(const Vec3& a, const Vec3& b, const LccpConfig& config, Visit visit) {
  const int samples = std::max(2, static_cast<int>((b - a).norm() / config.voxels.voxel_size_m));
  for (int k = 1; k < samples; ++k) {
    if (!visit(a + (b - a) * (static_cast<float>(k) / static_cast<float>(samples)))) return false;
  }
  return true;
}

// How far apart in depth a point seen and a sample may lie and still meet:
// the sensor's depth tolerance plus a voxel.
float meeting_margin(const Vec3& x, const LccpConfig& config) {
  return config.sensor.depth_tolerance_m(x.z()) + config.voxels.voxel_size_m;
}

// Whether the sensor cannot see the segment from a (on part p) to b (on part
// q) for a third object: no sample on it is seen past or falls on a point of
// no part (the support's: the gap is the table), none lies behind p or
// q themselves (they are then at different depths, one behind the other),
// at least half are hidden by (or meet) another part, and at most half fall
// where nothing was seen (the projector's shadow beside an occluder). Where
// the segment leaves p and where it reaches q, the third part seen is nearer
// than it: each part's edge there is an occlusion boundary, a jump in depth.
// A part that meets the third part at its edge (no jump) ends against it: a
// board leaning on a box is not continued through the box.
bool hidden_segment(const SeenDepth& seen, const Vec3& a, const Vec3& b, std::uint32_t p, std::uint32_t q,
                    const LccpConfig& config) {
  int samples = 0, hidden = 0, empty = 0;
  bool first_in_front = false, last_in_front = false;  // the first and the last third-part samples
  const bool unseen = every_sample(a, b, config, [&](const Vec3& x) {
    ++samples;
    const std::optional<Seen> first = seen.at(x);
    if (!first) return ++empty, true;
    const float margin = meeting_margin(x, config);
    const bool own = first->part == p || first->part == q;
    if (first->part == 0 || first->depth > x.z() + margin || (own && first->depth < x.z() - margin)) return false;
    if (own) return true;
    last_in_front = first->depth < x.z() - margin;
    if (hidden++ == 0) first_in_front = last_in_front;
    return true;
  });
  return unseen && 2 * hidden >= samples && 2 * empty <= samples && first_in_front && last_in_front;
}

// Whether the sensor sees past a sample of the segment from a to b.
bool seen_past(const SeenDepth& seen, const Vec3& a, const Vec3& b, const LccpConfig& config) {
  return !every_sample(a, b, config, [&](const Vec3& x) {
    const std::optional<Seen> first = seen.at(x);
    return !first || first->depth <= x.z() + meeting_margin(x, config);
  });
}

// One plane continues from patch a to patch b: their normals within
// beta_thresh (the paper's bias for what counts as flat, eq. (1)) and their
// offset along them within the sensor's depth tolerance.
bool continues(const Patch& a, const Patch& b, const LccpConfig& config) {
  if (normal_angle_deg(a, b) > config.convexity.beta_thresh_deg) return false;
  const float slack = config.sensor.depth_tolerance_m(0.5f * (a.centroid.z() + b.centroid.z()));
  return step_distance_m(a, b) <= slack;
}

// Whether patch a faces up: within upward_max_tilt_deg of `up`, the support's normal.
bool faces_up(const Patch& a, const LccpConfig& config, const Vec3& up) {
  return a.normal.dot(up) >= config.grouping.cos_upward();
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

// The highest of `members` (supervoxels) above or below supervoxel i: within
// `reach` of it across the support's normal.
Vec3 top_above(const SegmentationWork& w, std::span<const std::uint32_t> members, std::uint32_t i, float reach) {
  const Plane& plane = w.support->plane;
  const Vec3& at = w.supervoxels.centroids[i];
  Vec3 top = at;
  for (const std::uint32_t s : members) {
    const Vec3& c = w.supervoxels.centroids[s];
    const Vec3 d = c - at;
    if ((d - d.dot(plane.normal) * plane.normal).norm() <= reach && plane.distance(c) > plane.distance(top)) top = c;
  }
  return top;
}

// The centroids, in the support's plane coordinates, of the supervoxels of
// `members` on the upward face at `height` over the support: facing up, at
// that height within the sensor's depth tolerance. Appended to `face`.
void upward_face(const SegmentationWork& w, std::span<const std::uint32_t> members, float height,
                 const LccpConfig& config, std::vector<Vec2d>& face) {
  const Plane& plane = w.support->plane;
  const InPlane frame(plane.normal.cast<double>());
  for (const std::uint32_t s : members) {
    const Patch patch{w.supervoxels.centroids[s], w.supervoxels.normals[s]};
    const float slack = config.sensor.depth_tolerance_m(patch.centroid.z());
    if (faces_up(patch, config, plane.normal) && std::abs(plane.distance(patch.centroid) - height) <= slack) {
      face.push_back(frame(patch.centroid.cast<double>()));
    }
  }
}

// Whether the sensor sees past a sample of the convex polygon `hull` (support
// plane coordinates) lifted to `height` over the support: samples one voxel
// size apart.
bool seen_past_face(const SeenDepth& seen, std::span<const Vec2d> hull, const Plane& plane, float height,
                    const LccpConfig& config) {
  const InPlane frame(plane.normal.cast<double>());
  const Eigen::Vector3d lift = static_cast<double>(height - plane.d) * plane.normal.cast<double>();
  Vec2d lo = hull[0], hi = hull[0];
  for (const Vec2d& corner : hull) lo = lo.cwiseMin(corner), hi = hi.cwiseMax(corner);
  const double step = config.voxels.voxel_size_m;
  for (double u = lo.x(); u <= hi.x(); u += step) {
    for (double v = lo.y(); v <= hi.y(); v += step) {
      if (!inside_hull(hull, {u, v})) continue;
      const Vec3 x = (u * frame.e1 + v * frame.e2 + lift).cast<float>();
      const std::optional<Seen> first = seen.at(x);
      if (first && first->depth > x.z() + meeting_margin(x, config)) return true;
    }
  }
  return false;
}

// Whether upward patches a (of part p, its supervoxels `p_members`) and b (of
// q) lie on one face the sensor cannot see past: at one height over the
// support (within the sensor's depth tolerance), and no sample of the convex
// hull of both parts' upward faces at that height seen past. The tops of two
// things of one height on one table are one plane by coincidence; a face is
// convex, so were they one, it would hold that hull. Beside or behind the
// shorter of two such things the sensor sees past it, unless the two are
// aligned and their gap hidden.
bool one_face_hidden(const SegmentationWork& w, const SeenDepth& seen, const LccpConfig& config,
                     std::span<const std::uint32_t> p_members, std::span<const std::uint32_t> q_members,
                     const Patch& a, const Patch& b) {
  const Plane& plane = w.support->plane;
  const float height = plane.distance(a.centroid);
  if (std::abs(plane.distance(b.centroid) - height) > config.sensor.depth_tolerance_m(a.centroid.z())) return false;
  std::vector<Vec2d> face, hull;
  upward_face(w, p_members, height, config, face);
  upward_face(w, q_members, height, config, face);
  convex_hull_into(face, hull);
  return hull.size() >= 3 && !seen_past_face(seen, hull, plane, height, config);
}

// Whether parts p and q (0-based; their supervoxels `members`) continue each
// other behind a third object across one of their facing pairs: one plane
// continues from patch to patch, and the sensor cannot see the segment
// between them (hidden_segment). A plane facing up is a top: one face the
// sensor sees past nowhere (one_face_hidden). Any other plane: the sensor sees
// past no sample of the segment between the parts' tops above the two
// patches. One convex face (eq. (5) holds between its patches) through both
// tops holds that segment: a tall box and a low one beside it, their feet
// behind one nearer box, are two.
bool continue_hidden(const SegmentationWork& w, const SeenDepth& seen, const LccpConfig& config,
                     const Pairs& facing, const Grouped<std::uint32_t>& members, std::uint32_t p, std::uint32_t q) {
  const Vec3 up = w.support->plane.normal;
  const float reach = 2.0f * config.supervoxels.seed_size_m;
  for (const auto& [i, j] : facing) {
    const Patch a{w.supervoxels.centroids[i], w.supervoxels.normals[i]};
    const Patch b{w.supervoxels.centroids[j], w.supervoxels.normals[j]};
    if (!continues(a, b, config) || !hidden_segment(seen, a.centroid, b.centroid, p + 1, q + 1, config)) continue;
    if (faces_up(a, config, up)) {
      if (one_face_hidden(w, seen, config, members[p], members[q], a, b)) return true;
    } else if (!seen_past(seen, top_above(w, members[p], i, reach), top_above(w, members[q], j, reach), config)) {
      return true;
    }
  }
  return false;
}

// Calls visit(i, j, dx, dy) for every pixel i of an organized cloud and each
// of its 4-neighbours j, (dx, dy) the offset from j's pixel to i's.
template <class Visit>
void for_each_neighbour_pair(const CloudView& cloud, Visit visit) {
  const std::size_t width = cloud.width, n = cloud.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (i % width > 0) visit(i, i - 1, 1.0f, 0.0f);
    if (i % width + 1 < width) visit(i, i + 1, -1.0f, 0.0f);
    if (i >= width) visit(i, i - width, 0.0f, 1.0f);
    if (i + width < n) visit(i, i + width, 0.0f, -1.0f);
  }
}

// Where a loose part meets a nearer object in the image: the part's pixel of
// a pair of 4-neighbouring pixels whose other pixel is one of the object's
// parts, nearer by at most max_gap. Sorted by (part, object, pixel).
struct Border {
  std::uint32_t part = 0, object = 0;  // 0-based part; object as object_of gives it
  std::size_t pixel = 0;               // the part's
  friend auto operator<=>(const Border&, const Border&) = default;
};

std::vector<Border> borders_behind(const SegmentationWork& w, const std::vector<std::uint8_t>& loose,
                                   const std::vector<std::uint32_t>& object_of, float max_gap) {
  const Labels& labels = w.result.labels;
  const auto none = static_cast<std::uint32_t>(object_of.size());
  std::vector<Border> borders;
  for_each_neighbour_pair(w.cloud, [&](std::size_t i, std::size_t j, float, float) {  // i's loose part behind j's object
    const std::uint32_t a = labels[i], b = labels[j];
    if (a == 0 || !loose[a - 1] || b == 0 || object_of[b - 1] == none) return;
    const float behind = w.cloud.points[i].z() - w.cloud.points[j].z();
    if (behind > 0.0f && behind <= max_gap) borders.push_back({a - 1, object_of[b - 1], i});
  });
  std::sort(borders.begin(), borders.end());
  return borders;
}

// Whether a point of `object` (as object_of gives parts' objects) lies within
// `reach` of pixel i's point, among the pixels within reach of it (metres, as
// the image shows them at i's depth: reach f / z pixels each way).
bool object_within_reach(const SegmentationWork& w, std::size_t i, const std::vector<std::uint32_t>& object_of,
                         std::uint32_t object, float reach, float focal_px) {
  const Vec3& p = w.cloud.points[i];
  const auto width = static_cast<long>(w.cloud.width), height = static_cast<long>(w.cloud.height);
  const long r = static_cast<long>(std::ceil(reach * focal_px / p.z()));
  const long y = static_cast<long>(i) / width, x = static_cast<long>(i) % width;
  for (long v = std::max(0L, y - r); v <= std::min(height - 1, y + r); ++v) {
    for (long u = std::max(0L, x - r); u <= std::min(width - 1, x + r); ++u) {
      const auto j = static_cast<std::size_t>(v * width + u);
      const std::uint32_t label = w.result.labels[j];
      if (label != 0 && object_of[label - 1] == object && (w.cloud.points[j] - p).norm() <= reach) return true;
    }
  }
  return false;
}

// Whether the sensor sees the support under most of `members` (supervoxels):
// the first point seen toward a supervoxel's foot on the plane is the
// support's (no part's), at the foot's depth.
bool support_seen_under(const SegmentationWork& w, const SeenDepth& seen, std::span<const std::uint32_t> members,
                        const LccpConfig& config) {
  const Plane& plane = w.support->plane;
  std::size_t under = 0;
  for (const std::uint32_t s : members) {
    const Vec3& c = w.supervoxels.centroids[s];
    const Vec3 foot = c - plane.distance(c) * plane.normal;
    const std::optional<Seen> first = seen.at(foot);
    const float margin = config.sensor.depth_tolerance_m(foot.z()) + config.voxels.voxel_size_m;
    under += first && first->part == 0 && std::abs(first->depth - foot.z()) <= margin;
  }
  return 2 * under > members.size();
}

// Whether the pixel at offset (dx, dy) from p's pixel is the one above it in
// the image: the direction p's pixel moves in as p rises along the support's
// normal n (u = f x / z, v = f y / z: d(u, v) along n is proportional to
// (n_x z - x n_z, n_y z - y n_z)) lies within 45 deg of the offset.
bool above_in_image(const Vec3& p, const Vec3& n, float dx, float dy) {
  const float ux = n.x() * p.z() - p.x() * n.z(), uy = n.y() * p.z() - p.y() * n.z();
  return dx * ux + dy * uy >= std::numbers::sqrt2_v<float> / 2 * std::hypot(ux, uy);
}

// One pixel pair of an image border where part `outer` hides part `inner`
// (labels - 1): inner's pixel is the one above outer's, and farther. `rim`:
// the pair shows inner over outer's rim (rim_pair).
struct OverBorder {
  std::uint32_t inner = 0, outer = 0;
  bool rim = false;
  friend auto operator<=>(const OverBorder&, const OverBorder&) = default;
};

// Whether the sensor sees point pi (of a part whose top is `inner_top` over the
// support) over a rim at pj (of a part whose top is `outer_top`): pj at its
// part's top, on a surface that does not face up (the top of a wall, not the
// edge of a top face); pi below that top (inside); and both tops at one
// height (the near and the far side of one rim). Heights within the
// sensor's depth tolerance and a voxel (meeting_margin).
bool rim_pair(const SegmentationWork& w, const LccpConfig& config, std::size_t i, std::size_t j, float inner_top,
              float outer_top) {
  const Plane& plane = w.support->plane;
  const Vec3& pj = w.cloud.points[j];
  const float margin = meeting_margin(pj, config);
  if (!(std::abs(inner_top - outer_top) <= margin) || plane.distance(pj) < outer_top - margin) return false;
  if (plane.distance(w.cloud.points[i]) >= outer_top - margin) return false;
  const std::uint32_t v = w.grid.voxel_of_point[j];
  const Patch at_j{pj, v == kNoVoxel ? plane.normal : w.normals.directions[v]};
  return !faces_up(at_j, config, plane.normal) && !faces_up(at_j, config, -plane.normal);
}

// Every pixel pair where a part hides the part seen above it in the image,
// farther by more than meeting_margin (an occlusion boundary). Sorted.
std::vector<OverBorder> borders_over(const SegmentationWork& w, const LccpConfig& config,
                                     const std::vector<float>& tops) {
  const Labels& labels = w.result.labels;
  const Vec3& up = w.support->plane.normal;
  std::vector<OverBorder> borders;
  for_each_neighbour_pair(w.cloud, [&](std::size_t i, std::size_t j, float dx, float dy) {  // i above j?
    const std::uint32_t in = labels[i], out = labels[j];
    if (in == 0 || out == 0 || in == out || !above_in_image(w.cloud.points[j], up, dx, dy)) return;
    if (w.cloud.points[i].z() - w.cloud.points[j].z() <= meeting_margin(w.cloud.points[j], config)) return;
    borders.push_back({in - 1, out - 1, rim_pair(w, config, i, j, tops[in - 1], tops[out - 1])});
  });
  std::sort(borders.begin(), borders.end());
  return borders;
}

}  // namespace

std::vector<std::pair<std::uint32_t, std::uint32_t>> hidden_continuations(
    const SegmentationWork& w, const SeenDepth& seen, const LccpConfig& config,
    const std::vector<std::uint8_t>& eligible, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& adjacent) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  if (!w.support) return pairs;
  const Grouped<std::uint32_t> members = supervoxels_of_parts(w);
  Pairs facing;
  for (std::uint32_t p = 0; p < members.size(); ++p) {
    for (std::uint32_t q = p + 1; q < members.size() && eligible[p]; ++q) {
      if (!eligible[q] || std::binary_search(adjacent.begin(), adjacent.end(), std::pair{p, q})) continue;
      facing_pairs(w, members[p], members[q], config, facing);
      if (continue_hidden(w, seen, config, facing, members, p, q)) pairs.emplace_back(p, q);
    }
  }
  return pairs;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> held_behind(const SegmentationWork& w, const SeenDepth& seen,
                                                                 const LccpConfig& config,
                                                                 const std::vector<std::uint8_t>& loose,
                                                                 const std::vector<std::uint32_t>& object_of) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> held;
  const bool any_loose = std::find(loose.begin(), loose.end(), 1) != loose.end();
  if (!any_loose || !w.cloud.organized() || !w.support) return held;
  const std::vector<Border> borders = borders_behind(w, loose, object_of, config.grouping.occluded_gap_m);
  if (borders.empty()) return held;
  const Grouped<std::uint32_t> members = supervoxels_of_parts(w);
  const float reach = config.supervoxels.seed_size_m;
  std::size_t most = 0;
  for (std::size_t first = 0, last = 0; first < borders.size(); first = last) {
    const std::uint32_t part = borders[first].part, object = borders[first].object;
    bool near = false;  // each border pixel once (a pixel may border the object on two sides)
    for (last = first; last < borders.size() && borders[last].part == part && borders[last].object == object; ++last) {
      const bool again = last > first && borders[last].pixel == borders[last - 1].pixel;
      near = near ||
             (!again && object_within_reach(w, borders[last].pixel, object_of, object, reach, config.sensor.focal_px));
    }
    if (!near || !support_seen_under(w, seen, members[part], config)) continue;
    if (held.empty() || held.back().first != part) {
      held.emplace_back(part, object), most = last - first;
    } else if (last - first > most) {
      held.back().second = object, most = last - first;
    }
  }
  return held;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> seen_over_rims(const SegmentationWork& w,
                                                                   const LccpConfig& config,
                                                                   const std::vector<float>& tops) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> inside;
  if (!w.cloud.organized() || !w.support) return inside;
  const std::vector<OverBorder> borders = borders_over(w, config, tops);
  for (std::size_t first = 0, last = 0; first < borders.size(); first = last) {
    const auto same = [&](std::size_t k) {
      return borders[k].inner == borders[first].inner && borders[k].outer == borders[first].outer;
    };
    std::size_t rims = 0;
    for (last = first; last < borders.size() && same(last); ++last) rims += borders[last].rim;
    if (2 * rims > last - first) inside.emplace_back(borders[first].inner, borders[first].outer);
  }
  return inside;
}

}  // namespace lccp::detail
