// Per-segment geometry for a grasp planner (paper Sec. III.C: "the pose of the
// handle was calculated from its 3D shape").
//
// Two passes over the points, each parallel over fixed blocks of points whose
// per-segment partial results are merged in block order, so that every figure is
// the same whatever the thread count:
//   1. moments: count, sum, sum of outer products and,
//      with a support plane, the span of heights and the extreme points in
//      eight in-plane directions;
//   2. spreads: extents along the principal axes and, with a plane, the hull
//      candidates (the points outside the octagon of those extremes), listed
//      per block and then gathered by segment into one array.
// Between and after them, per segment (serial, segments in parallel): the 3x3
// eigenproblem, the 2D convex hull and the minimum-area rectangle; last, the
// segment adjacency from the supervoxel graph.
#include "lccp/objects/geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "convex_hull.hpp"
#include "lccp/core/convexity.hpp"
#include "lccp/core/grouped.hpp"
#include "lccp/error.hpp"

namespace lccp {
namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Paper Sec. III.C: the robot grasps "from top or from side depending on the
// orientation of the handle". A main axis tilted less than this from the
// vertical is an upright handle, grasped from the side; a flatter one from the top.
constexpr double kUprightHandleMaxTiltDeg = 45.0;

// Points per block of the per-segment reductions. The blocks depend on the cloud
// size and segment count only, never on the thread count, and their partial
// results are merged in block order: results do not depend on the threads.
constexpr std::size_t kBlockPoints = 16384;
// At most this many per-block, per-segment partials at once (a few MB; bounds
// the memory when a cloud has very many segments: fewer, larger blocks).
constexpr std::size_t kMaxPartials = std::size_t{1} << 14;

struct Blocks {
  std::size_t size = 1;   // points per block
  std::size_t count = 0;  // blocks
};

Blocks fixed_blocks(std::size_t points, std::size_t segments) {
  const std::size_t most = std::max<std::size_t>(1, kMaxPartials / std::max<std::size_t>(1, segments));
  const std::size_t wanted = std::clamp<std::size_t>((points + kBlockPoints - 1) / kBlockPoints, 1, most);
  Blocks blocks;
  blocks.size = std::max<std::size_t>(1, (points + wanted - 1) / wanted);
  blocks.count = (points + blocks.size - 1) / blocks.size;
  return blocks;
}

// Per-segment reduction over the points with a label 1..K: fold(acc, i, k, b)
// adds point i of segment k (0-based) to block b's partial, each block on one
// thread; the partials are then merged with merge(into, from) in block order.
template <typename Acc, typename Fold, typename Merge>
std::vector<Acc> reduce_per_segment(const Labels& labels, std::size_t K, Fold&& fold, Merge&& merge) {
  const Blocks blocks = fixed_blocks(labels.size(), K);
  std::vector<std::vector<Acc>> partials(blocks.count);
  tbb::parallel_for(std::size_t{0}, blocks.count, [&](std::size_t b) {
    partials[b].resize(K);
    const std::size_t end = std::min(labels.size(), (b + 1) * blocks.size);
    for (std::size_t i = b * blocks.size; i < end; ++i) {
      if (labels[i] != 0 && labels[i] <= K) fold(partials[b][labels[i] - 1], i, labels[i] - 1, b);
    }
  });
  std::vector<Acc> total(K);
  tbb::parallel_for(std::size_t{0}, K, [&](std::size_t k) {
    for (const std::vector<Acc>& partial : partials) merge(total[k], partial[k]);
  });
  return total;
}

// --- the support plane's frame ------------------------------------------------------

// An orthonormal right-handed frame (e1, e2, n) with n the plane normal: a point
// p has plane coordinates (p . e1, p . e2) and height p . n.
struct PlaneFrame {
  Vec3 e1, e2, n;
  Vec2 in_plane(const Vec3& p) const { return {p.dot(e1), p.dot(e2)}; }
  Vec3 from_plane(const Vec2& u, double height) const { return u.x() * e1 + u.y() * e2 + height * n; }
};

PlaneFrame plane_frame(const Plane& plane) {
  const Vec3 n = plane.normal.cast<double>().normalized();
  Eigen::Index least = 0;
  n.cwiseAbs().minCoeff(&least);  // the coordinate axis farthest from n
  const Vec3 e1 = n.cross(Vec3::Unit(least)).normalized();
  return {e1, n.cross(e1), n};  // e1 x (n x e1) = n
}

// The eight compass directions of the plane, counter-clockwise. A segment's
// extreme points along them span an octagon whose interior points cannot be
// hull vertices: the Akl-Toussaint heuristic (S. G. Akl, G. T. Toussaint, "A
// fast convex hull algorithm", Inf. Process. Lett. 7(5), 1978).
constexpr std::array<std::array<double, 2>, 8> kCompass{
    {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}}};

// With a support plane: a segment's span of heights and its compass extremes.
struct Footprint {
  double height_lo = kInf;
  double height_hi = -kInf;
  std::array<double, 8> extreme_value{-kInf, -kInf, -kInf, -kInf, -kInf, -kInf, -kInf, -kInf};
  std::array<Vec2, 8> extreme{};  // the first point reaching extreme_value, plane coordinates

  void fold(const Vec2& u, double height) {
    height_lo = std::min(height_lo, height), height_hi = std::max(height_hi, height);
    for (std::size_t j = 0; j < kCompass.size(); ++j) {
      const double value = kCompass[j][0] * u.x() + kCompass[j][1] * u.y();
      if (value > extreme_value[j]) extreme_value[j] = value, extreme[j] = u;
    }
  }
  void merge(const Footprint& from) {  // ties keep the earlier block's point
    height_lo = std::min(height_lo, from.height_lo), height_hi = std::max(height_hi, from.height_hi);
    for (std::size_t j = 0; j < kCompass.size(); ++j) {
      if (from.extreme_value[j] > extreme_value[j]) {
        extreme_value[j] = from.extreme_value[j], extreme[j] = from.extreme[j];
      }
    }
  }
};

// --- pass 1: moments ------------------------------------------------------------------

struct Moments {
  double n = 0;
  Vec3 sum = Vec3::Zero();
  // The sum of p p^T, its upper triangle (xx, xy, xz, yy, yz, zz): it is
  // symmetric, and p_i p_j is p_j p_i exactly, so the lower half is a copy.
  Eigen::Matrix<double, 6, 1> outer = Eigen::Matrix<double, 6, 1>::Zero();
  Mat3 outer_matrix() const {
    Mat3 m;
    m << outer[0], outer[1], outer[2], outer[1], outer[3], outer[4], outer[2], outer[4], outer[5];
    return m;
  }
  Footprint footprint;             // with a plane
};

std::vector<Moments> segment_moments(const SegmentationWork& w, const SegmentLabels& segments,
                                     const std::optional<PlaneFrame>& frame) {
  const auto fold = [&](Moments& m, std::size_t i, std::size_t, std::size_t) {
    const Vec3 p = w.cloud.points[i].cast<double>();
    m.n += 1;
    m.sum += p;
    m.outer += Eigen::Matrix<double, 6, 1>(p.x() * p.x(), p.x() * p.y(), p.x() * p.z(), p.y() * p.y(), p.y() * p.z(),
                                          p.z() * p.z());
    if (frame) m.footprint.fold(frame->in_plane(p), p.dot(frame->n));
  };
  const auto merge = [](Moments& into, const Moments& from) {
    into.n += from.n, into.sum += from.sum, into.outer += from.outer;
    into.footprint.merge(from.footprint);
  };
  return reduce_per_segment<Moments>(segments.points, segments.count, fold, merge);
}

// Centroid and principal axes (PCA: eigenvectors of the covariance), columns by
// decreasing variance, the third the cross product of the first two (right-handed).
struct Principal {
  Vec3 centroid = Vec3::Zero();
  Mat3 axes = Mat3::Identity();
};

Principal principal_frame(const Moments& m) {
  if (m.n == 0) return {};
  Principal p;
  p.centroid = m.sum / m.n;
  const Mat3 covariance = m.outer_matrix() / m.n - p.centroid * p.centroid.transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(covariance);  // eigenvalues ascending
  p.axes = solver.eigenvectors().rowwise().reverse();
  p.axes.col(2) = p.axes.col(0).cross(p.axes.col(1));
  return p;
}

// --- pass 2: spreads and hull candidates --------------------------------------------

// The convex polygon of a segment's compass extremes, counter-clockwise (support
// points of directions in angular order), repeated vertices dropped; stored as
// its edges' lines n . p = offset, n the inward normal.
class Octagon {
 public:
  explicit Octagon(const Footprint& f) {
    std::array<Vec2, 8> vertex{};
    std::size_t count = 0;
    for (const Vec2& p : f.extreme) {
      if (count == 0 || (p != vertex[count - 1] && p != vertex[0])) vertex[count++] = p;
    }
    edges_ = count < 3 ? 0 : count;  // fewer than three vertices: no inside
    for (std::size_t j = 0; j < edges_; ++j) {
      const Vec2 edge = vertex[(j + 1) % count] - vertex[j];
      normal_[j] = Vec2(-edge.y(), edge.x());
      offset_[j] = normal_[j].dot(vertex[j]);
    }
  }
  // Strictly inside: strictly left of every edge.
  bool contains(const Vec2& p) const {
    for (std::size_t j = 0; j < edges_; ++j) {
      if (!(normal_[j].dot(p) > offset_[j])) return false;
    }
    return edges_ > 0;
  }

 private:
  std::array<Vec2, 8> normal_{};
  std::array<double, 8> offset_{};
  std::size_t edges_ = 0;
};

struct Spread {
  Vec3 lo = Vec3::Constant(kInf);  // along the principal axes, from the centroid
  Vec3 hi = Vec3::Constant(-kInf);
};

// With a plane: every segment's hull candidates (plane coordinates of its points
// outside its octagon, a superset of its hull vertices), in point order.
using HullCandidates = Grouped<Vec2>;

// One block's hull candidates, (segment, point) in point order.
using BlockCandidates = std::vector<std::pair<std::uint32_t, Vec2>>;

// Spread along the principal axes and, with a plane, the hull candidates.
std::vector<Spread> segment_spreads(const SegmentationWork& w, const SegmentLabels& segments,
                                    const std::vector<Principal>& principal, const std::vector<Moments>& moments,
                                    const std::optional<PlaneFrame>& frame, HullCandidates& candidates) {
  std::vector<Octagon> octagons;
  if (frame) octagons.reserve(moments.size());
  for (std::size_t k = 0; frame && k < moments.size(); ++k) octagons.emplace_back(moments[k].footprint);
  std::vector<BlockCandidates> outside(fixed_blocks(segments.points.size(), principal.size()).count);
  const auto fold = [&](Spread& s, std::size_t i, std::size_t k, std::size_t b) {
    const Vec3 p = w.cloud.points[i].cast<double>();
    const Vec3 along = principal[k].axes.transpose() * (p - principal[k].centroid);
    s.lo = s.lo.cwiseMin(along), s.hi = s.hi.cwiseMax(along);
    if (!frame) return;
    const Vec2 u = frame->in_plane(p);
    if (!octagons[k].contains(u)) outside[b].emplace_back(static_cast<std::uint32_t>(k), u);
  };
  const auto merge = [](Spread& into, const Spread& from) {
    into.lo = into.lo.cwiseMin(from.lo), into.hi = into.hi.cwiseMax(from.hi);
  };
  auto spreads = reduce_per_segment<Spread>(segments.points, principal.size(), fold, merge);
  candidates = group_by_key<Vec2>(principal.size(), [&](auto emit) {
    for (const BlockCandidates& block : outside) {
      for (const auto& [k, u] : block) emit(k, u);
    }
  });
  return spreads;
}

// --- per segment: hull and rectangle ------------------------------------------------


// A rectangle in plane coordinates: side direction u (unit), v = u rotated by
// +90 deg, and the spans [lo, hi] of the enclosed points along each.
struct Rectangle {
  Vec2 u = Vec2::UnitX();
  Vec2 lo = Vec2::Zero();
  Vec2 hi = Vec2::Zero();
  Vec2 v() const { return {-u.y(), u.x()}; }
  double area() const { return (hi - lo).prod(); }
};

// Moves vertex index `at` forward along a convex polygon while that increases
// the projection on `direction` (one caliper of the rotating calipers).
std::size_t advance(const std::vector<Vec2>& hull, std::size_t at, const Vec2& direction) {
  for (std::size_t steps = 0; steps < hull.size(); ++steps) {
    const std::size_t next = (at + 1) % hull.size();
    if (!((hull[next] - hull[at]).dot(direction) > 0)) break;
    at = next;
  }
  return at;
}

// The minimum-area enclosing rectangle has a side collinear with a hull edge
// (H. Freeman, R. Shapira, "Determining the minimum-area encasing rectangle for
// an arbitrary closed curve", Commun. ACM 18(7), 1975); rotating calipers visit
// every edge's rectangle in O(h) (G. T. Toussaint, "Solving geometric problems
// with the rotating calipers", Proc. IEEE MELECON, 1983). First minimum wins.
Rectangle min_area_rectangle(const std::vector<Vec2>& hull) {
  if (hull.size() < 2) return hull.empty() ? Rectangle{} : Rectangle{Vec2::UnitX(), hull[0], hull[0]};
  Rectangle best;
  double best_area = kInf;
  std::size_t right = 0, top = 0, left = 0;  // extreme along +u, +v, -u
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec2 u = (hull[(i + 1) % hull.size()] - hull[i]).normalized();
    const Vec2 v(-u.y(), u.x());  // inward: the hull is counter-clockwise
    right = advance(hull, i == 0 ? 0 : right, u);
    top = advance(hull, i == 0 ? right : top, v);
    left = advance(hull, i == 0 ? top : left, -u);
    const Rectangle r{u, {u.dot(hull[left]), v.dot(hull[i])}, {u.dot(hull[right]), v.dot(hull[top])}};
    if (r.area() < best_area) best = r, best_area = r.area();
  }
  return best;
}

// --- per segment: boxes -------------------------------------------------------------

// With a support plane: the minimum-area rectangle of the footprint, its longer
// side first, the plane normal third (right-handed), heights from the points.
OrientedBox box_on_plane(const Rectangle& r, const Footprint& f, const PlaneFrame& frame) {
  const Vec2 span = r.hi - r.lo;
  const Vec2 first = span.x() >= span.y() ? r.u : r.v();
  const Vec3 a1 = frame.from_plane(first, 0).normalized();
  const Vec2 center = 0.5 * (r.lo.x() + r.hi.x()) * r.u + 0.5 * (r.lo.y() + r.hi.y()) * r.v();
  OrientedBox box;
  box.center = frame.from_plane(center, 0.5 * (f.height_lo + f.height_hi)).cast<float>();
  box.axes << a1.cast<float>(), frame.n.cross(a1).cast<float>(), frame.n.cast<float>();
  box.extents = Vec3(span.maxCoeff(), span.minCoeff(), f.height_hi - f.height_lo).cast<float>();
  return box;
}

// Without one: the principal axes and the points' spread along them.
OrientedBox principal_box(const Principal& p, const Spread& s) {
  OrientedBox box;
  box.center = (p.centroid + p.axes * (0.5 * (s.lo + s.hi))).cast<float>();
  box.axes = p.axes.cast<float>();
  box.extents = (s.hi - s.lo).cast<float>();
  return box;
}

// A thread's buffers for one segment's hull at a time: reused, so that a
// segment costs no allocation once they have grown to the largest.
struct HullScratch {
  std::vector<Vec2> points, hull;
};

std::vector<OrientedBox> segment_boxes(const std::vector<Principal>& principal, const std::vector<Moments>& moments,
                                       const std::vector<Spread>& spreads, const std::optional<PlaneFrame>& frame,
                                       const HullCandidates& candidates) {
  std::vector<OrientedBox> boxes(spreads.size());
  tbb::enumerable_thread_specific<HullScratch> scratch;
  tbb::parallel_for(std::size_t{0}, boxes.size(), [&](std::size_t k) {
    if (!frame) {
      boxes[k] = principal_box(principal[k], spreads[k]);
      return;
    }
    HullScratch& s = scratch.local();
    s.points.assign(candidates[k].begin(), candidates[k].end());
    detail::convex_hull_into(s.points, s.hull);
    boxes[k] = box_on_plane(min_area_rectangle(s.hull), moments[k].footprint, *frame);
  });
  return boxes;
}

// --- per segment: normal, grasp -----------------------------------------------------

// Per segment, the sum of its voxels' normals, each weighted by its points (all
// points of a voxel carry its label: labels come from voxels). Serial, in voxel order.
std::vector<Vec3> normal_sums(const SegmentationWork& w, const SegmentLabels& segments) {
  const std::size_t K = segments.count;
  std::vector<Vec3> sums(K, Vec3::Zero());
  const CompressedRows& members = w.grid.points;
  for (std::size_t v = 0; v < w.grid.size(); ++v) {
    if (members.count(v) == 0) continue;
    const std::uint32_t label = segments.points[*members.begin(v)];
    if (label != 0 && label <= K) sums[label - 1] += members.count(v) * w.normals.directions[v].cast<double>();
  }
  return sums;
}

// The normalized mean of the member voxels' normals (weighted by their points),
// turned to face the sensor at the origin; the direction to the sensor if they cancel.
Vec3 mean_normal(const Vec3& normal_sum, const Vec3& centroid) {
  Vec3 n = normal_sum.squaredNorm() > 0 ? normal_sum : Vec3(-centroid);
  if (n.dot(centroid) > 0) n = -n;
  return n.squaredNorm() > 0 ? Vec3(n.normalized()) : Vec3(0, 0, -1);
}

Grasp grasp_hint(const Vec3& main_axis, const Vec3& up) {
  const double cos_max_tilt = std::cos(kUprightHandleMaxTiltDeg * std::numbers::pi / 180.0);
  return std::abs(main_axis.dot(up)) > cos_max_tilt ? Grasp::side : Grasp::top;
}

// --- adjacency ------------------------------------------------------------------------

// One vote per supervoxel edge between two segments (lo < hi): convex under the
// paper's basic criterion, eq. (1) without the bias (beta_thresh = 0):
// (n1 - n2) . (x1 - x2) > 0. Sorted by segment pair.
std::vector<std::array<std::uint32_t, 3>> boundary_votes(const SegmentationWork& w, const SegmentLabels& segments) {
  ConvexityConfig unbiased;
  unbiased.beta_thresh_deg = 0.0f;
  const std::vector<std::uint32_t>& segment = segments.supervoxels;
  const std::uint32_t K = segments.count;
  std::vector<std::array<std::uint32_t, 3>> votes;
  for (const Edge& e : w.edges) {
    const std::uint32_t a = segment[e.a], b = segment[e.b];
    if (a == b || a == 0 || b == 0 || a > K || b > K) continue;
    const Patch pa{w.supervoxels.centroids[e.a], w.supervoxels.normals[e.a]};
    const Patch pb{w.supervoxels.centroids[e.b], w.supervoxels.normals[e.b]};
    votes.push_back({std::min(a, b), std::max(a, b), convexity_criterion(pa, pb, unbiased) ? 1u : 0u});
  }
  std::sort(votes.begin(), votes.end());
  return votes;
}

// Two segments are adjacent when a supervoxel edge joins them; their boundary is
// convex when most of those edges are (ties concave). Lists by ascending id.
void add_adjacency(const SegmentationWork& w, const SegmentLabels& segments, std::vector<SegmentGeometry>& out) {
  const auto votes = boundary_votes(w, segments);
  for (std::size_t first = 0, last = 0; first < votes.size(); first = last) {
    std::size_t convex = 0;
    const auto same_pair = [&](std::size_t i) { return votes[i][0] == votes[first][0] && votes[i][1] == votes[first][1]; };
    for (last = first; last < votes.size() && same_pair(last); ++last) convex += votes[last][2];
    const Boundary boundary = 2 * convex > last - first ? Boundary::convex : Boundary::concave;
    const std::uint32_t lo = votes[first][0], hi = votes[first][1];
    out[lo - 1].adjacent.push_back({hi, boundary});
    out[hi - 1].adjacent.push_back({lo, boundary});
  }
  for (SegmentGeometry& g : out) {
    std::sort(g.adjacent.begin(), g.adjacent.end(), [](const Neighbour& a, const Neighbour& b) { return a.id < b.id; });
  }
}

void check_work(const SegmentationWork& w, const SegmentLabels& segments) {
  const bool complete = segments.points.size() == w.cloud.size() &&
                        w.grid.points.rows() == w.grid.size() && w.normals.size() == w.grid.size() &&
                        segments.supervoxels.size() == w.supervoxels.size();
  if (!complete) throw Error("describe_segments: the segmentation work is incomplete (run every stage first)");
}

SegmentGeometry describe(std::uint32_t id, const Moments& m, const Principal& p, const Spread& s,
                         const OrientedBox& box, const Vec3& normal_sum, const Vec3& up) {
  SegmentGeometry g;
  g.id = id;
  g.points = static_cast<std::uint64_t>(m.n);
  if (m.n == 0) return g;  // no points (LccpSegmenter makes none): defaults
  g.centroid = p.centroid.cast<float>();
  g.obb = box;
  g.principal_axes = p.axes.cast<float>();
  g.principal_extents = (s.hi - s.lo).cast<float>();
  g.mean_normal = mean_normal(normal_sum, p.centroid).cast<float>();
  g.grasp = grasp_hint(p.axes.col(0), up);
  return g;
}

}  // namespace

std::vector<SegmentGeometry> describe_segments(const SegmentationWork& work, const std::optional<Plane>& support) {
  return describe_segments(work, {work.result.labels, work.segment_of_supervoxel, work.result.segment_count}, support);
}

std::vector<SegmentGeometry> describe_segments(const SegmentationWork& work, const SegmentLabels& segments,
                                               const std::optional<Plane>& support) {
  check_work(work, segments);
  const std::size_t K = segments.count;
  const std::optional<PlaneFrame> frame = support ? std::optional(plane_frame(*support)) : std::nullopt;
  const std::vector<Moments> moments = segment_moments(work, segments, frame);
  std::vector<Principal> principal(K);
  tbb::parallel_for(std::size_t{0}, K, [&](std::size_t k) { principal[k] = principal_frame(moments[k]); });
  HullCandidates candidates;
  const std::vector<Spread> spreads = segment_spreads(work, segments, principal, moments, frame, candidates);
  const std::vector<OrientedBox> boxes = segment_boxes(principal, moments, spreads, frame, candidates);
  const std::vector<Vec3> normals = normal_sums(work, segments);
  const Vec3 up = frame ? frame->n : Vec3(0, -1, 0);  // without a plane: the sensor's up, -y
  std::vector<SegmentGeometry> out(K);
  tbb::parallel_for(std::size_t{0}, K, [&](std::size_t k) {
    const auto id = static_cast<std::uint32_t>(k + 1);
    out[k] = describe(id, moments[k], principal[k], spreads[k], boxes[k], normals[k], up);
  });
  add_adjacency(work, segments, out);
  return out;
}

}  // namespace lccp
