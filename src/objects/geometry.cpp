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
// Serial passes over the voxels (in voxel order) sum each segment's normals and,
// with a plane and where a segment's normals turn about an axis in it, the two
// circle fits that tell a cylinder lying on the plane.
// Between and after them, per segment (serial, segments in parallel): the 3x3
// eigenproblem, the 2D convex hull (widened to a lying cylinder's hidden back)
// and the minimum-area rectangle; last, the segment adjacency from the
// supervoxel graph.
#include "lccp/objects/geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
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
  double height = 0;  // the plane's own: p . n of its points
  Vec2 in_plane(const Vec3& p) const { return {p.dot(e1), p.dot(e2)}; }
  Vec3 from_plane(const Vec2& u, double height) const { return u.x() * e1 + u.y() * e2 + height * n; }
};

PlaneFrame plane_frame(const Plane& plane) {
  const Vec3 n = plane.normal.cast<double>().normalized();
  Eigen::Index least = 0;
  n.cwiseAbs().minCoeff(&least);  // the coordinate axis farthest from n
  const Vec3 e1 = n.cross(Vec3::Unit(least)).normalized();
  const double height = -plane.d / plane.normal.cast<double>().norm();
  return {e1, n.cross(e1), n, height};  // e1 x (n x e1) = n
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
  Footprint footprint;             // with a plane
};

Eigen::Matrix<double, 6, 1> upper_outer(const Vec3& a) {
  return {a.x() * a.x(), a.x() * a.y(), a.x() * a.z(), a.y() * a.y(), a.y() * a.z(), a.z() * a.z()};
}

Mat3 symmetric(const Eigen::Matrix<double, 6, 1>& u) {
  Mat3 m;
  m << u[0], u[1], u[2], u[1], u[3], u[4], u[2], u[4], u[5];
  return m;
}

std::vector<Moments> segment_moments(const SegmentationWork& w, const SegmentLabels& segments,
                                     const std::optional<PlaneFrame>& frame) {
  const auto fold = [&](Moments& m, std::size_t i, std::size_t, std::size_t) {
    const Vec3 p = w.cloud.points[i].cast<double>();
    m.n += 1;
    m.sum += p;
    m.outer += upper_outer(p);
    if (frame) m.footprint.fold(frame->in_plane(p), p.dot(frame->n));
  };
  const auto merge = [](Moments& into, const Moments& from) {
    into.n += from.n, into.sum += from.sum, into.outer += from.outer;
    into.footprint.merge(from.footprint);
  };
  return reduce_per_segment<Moments>(segments.points, segments.count, fold, merge);
}

// Per segment, each point with its voxel's normal m: the sums of m, of m m^T
// (upper triangle, as Moments::outer) and of p m^T. A voxel's points share its
// normal, so each voxel adds its point count times m, m m^T and its centroid
// times m^T. Serial, in voxel order.
struct NormalMoments {
  Vec3 sum = Vec3::Zero();
  Eigen::Matrix<double, 6, 1> outer = Eigen::Matrix<double, 6, 1>::Zero();
  Mat3 point_normal = Mat3::Zero();
};

// Per voxel, its segment's label (0: none): a voxel's points share it (labels
// come from voxels).
std::vector<std::uint32_t> voxel_labels(const SegmentationWork& w, const SegmentLabels& segments) {
  const CompressedRows& members = w.grid.points;
  std::vector<std::uint32_t> labels(w.grid.size(), 0);
  for (std::size_t v = 0; v < labels.size(); ++v) {
    if (members.count(v) == 0) continue;
    const std::uint32_t label = segments.points[*members.begin(v)];
    labels[v] = label <= segments.count ? label : 0;
  }
  return labels;
}

// Calls visit(v, k, n) for every voxel v of a segment k (0-based) with its n
// points, in voxel order.
template <typename Visit>
void for_each_segment_voxel(const SegmentationWork& w, const std::vector<std::uint32_t>& labels, Visit&& visit) {
  for (std::size_t v = 0; v < labels.size(); ++v) {
    if (labels[v] != 0) visit(v, labels[v] - 1, static_cast<double>(w.grid.points.count(v)));
  }
}

std::vector<NormalMoments> normal_moments(const SegmentationWork& w, const std::vector<std::uint32_t>& labels,
                                          std::size_t K) {
  std::vector<NormalMoments> out(K);
  for_each_segment_voxel(w, labels, [&](std::size_t v, std::size_t k, double n) {
    const Vec3 m = w.normals.directions[v].cast<double>();
    const Vec3 points_sum = n * w.grid.centroids[v].cast<double>();
    out[k].sum += n * m, out[k].outer += n * upper_outer(m), out[k].point_normal += points_sum * m.transpose();
  });
  return out;
}

// Centroid and principal axes (PCA: eigenvectors of the covariance), columns by
// decreasing variance, the third the cross product of the first two (right-handed).
struct Principal {
  Vec3 centroid = Vec3::Zero();
  Mat3 axes = Mat3::Identity();
  Vec3 lying_axis = Vec3::Zero();  // with a plane, of a cylinder lying on it (lying_axis()); zero: none
};

Principal principal_frame(const Moments& m) {
  if (m.n == 0) return {};
  Principal p;
  p.centroid = m.sum / m.n;
  const Mat3 covariance = symmetric(m.outer) / m.n - p.centroid * p.centroid.transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(covariance);  // eigenvalues ascending
  p.axes = solver.eigenvectors().rowwise().reverse();
  p.axes.col(2) = p.axes.col(0).cross(p.axes.col(1));
  return p;
}

// --- between the passes: could the segment be a cylinder lying on the support? -------

// A can or a bottle on its side shows the sensor half of its curved surface or
// less, so the footprint of its points misses the hidden back (a third to a
// half of the diameter). On a cylinder about an axis along a, every point's
// outward normal m is at right angles to a and turns with the point around it.
// So a segment is a candidate when, with q and m its points and normals
// projected across the axis lying in the support plane that its normals are
// most nearly at right angles to, the normals turn through at least 90 deg
// (var(m)) and point away from the axis, as the points do (cov(m, q) > 0: the
// outside of a cylinder, not a trough's inside). lying_cylinders() decides.

// var(m) of unit vectors spread evenly over an arc of 90 deg: 1 - (sin 45 deg / (pi / 4))^2.
constexpr double kMinNormalTurn = 0.189;

// The axis lying in the support plane that the normals are most nearly at right
// angles to (the least eigenvector of the in-plane part of sum m m^T), if the
// segment is a candidate; zero otherwise.
Vec3 lying_axis(const Moments& m, const NormalMoments& normals, const PlaneFrame& frame) {
  if (m.n < 3) return Vec3::Zero();
  Eigen::Matrix<double, 3, 2> in_plane;
  in_plane << frame.e1, frame.e2;
  const Eigen::Matrix2d scatter = in_plane.transpose() * symmetric(normals.outer) * in_plane;
  const Vec3 a = in_plane * Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(scatter).eigenvectors().col(0);
  const Mat3 across = Mat3::Identity() - a * a.transpose();
  const Vec3 mean_q = across * m.sum / m.n, mean_m = across * normals.sum / m.n;
  const double var_m = (across * symmetric(normals.outer)).trace() / m.n - mean_m.squaredNorm();
  const double cov = (across * normals.point_normal).trace() / m.n - mean_m.dot(mean_q);
  return var_m >= kMinNormalTurn && cov > 0 ? a : Vec3::Zero();
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

// The rectangle with sides along u (unit) and its normal around the points.
Rectangle rectangle_along(const std::vector<Vec2>& points, const Vec2& u) {
  Rectangle r{u, Vec2::Constant(kInf), Vec2::Constant(-kInf)};
  for (const Vec2& p : points) {
    const Vec2 q(u.dot(p), r.v().dot(p));
    r.lo = r.lo.cwiseMin(q), r.hi = r.hi.cwiseMax(q);
  }
  return r;
}

// --- per segment: a lying cylinder's circle and bounds ------------------------------

// The sums for an algebraic circle fit (I. Kasa, "A circle fitting procedure and
// its error analysis", IEEE Trans. Instrum. Meas. 25(1), 1976) across a lying
// axis: z = x^2 + y^2 against the regressors g = (x, y, 1) and, in the second
// fit, (t x, t, t^2), t the coordinate along the axis. If the true axis is
// turned by a small angle d, a point's x is x + d t, and z + D x + E y + F = 0
// becomes, to first order in d, z + D x + E y + F + 2 d t x + D d t = 0. And a
// radius that changes along the axis adds K t^2 (with t): K = 0 on a cylinder,
// 1 on a sphere (x^2 + y^2 + t^2 = R^2), whose every section is a circle too.
struct CircleSums {
  using Regressors = Eigen::Matrix<double, 6, 1>;
  Eigen::Index terms = 3;  // the regressors used: 3, or 6
  Eigen::Matrix<double, 6, 6> gg = Eigen::Matrix<double, 6, 6>::Zero();  // upper triangle
  Regressors zg = Regressors::Zero();
  double zz = 0;

  void add(const Vec3& q, double weight) {  // (x, y, t)
    const double z = q.x() * q.x() + q.y() * q.y();
    Regressors g;
    g << q.x(), q.y(), 1, q.z() * q.x(), q.z(), q.z() * q.z();
    for (Eigen::Index i = 0; i < terms; ++i) {
      for (Eigen::Index j = i; j < terms; ++j) gg(i, j) += weight * g[i] * g[j];
    }
    zg.head(terms) += weight * z * g.head(terms), zz += weight * z * z;
  }
};

// The cylinder's curved surface: its normals at right angles to the axis; an
// end's are along it. A voxel counts when its normal is within 30 deg of square
// to the lying axis.
constexpr double kMaxAxialNormal = 0.5;  // sin 30 deg

bool on_lying_surface(const Eigen::Vector3f& normal, const Principal& s) {
  return !s.lying_axis.isZero() && std::abs(normal.cast<double>().dot(s.lying_axis)) <= kMaxAxialNormal;
}

// A point's coordinates about a lying axis a, from the segment's centroid:
// across it (along n x a and along the plane normal n), then along it.
Vec3 axis_coordinates(const Vec3& p, const Principal& s, const PlaneFrame& frame) {
  const Vec3 d = p - s.centroid;
  return {d.dot(frame.n.cross(s.lying_axis)), d.dot(frame.n), d.dot(s.lying_axis)};
}

struct LyingCylinder {
  Vec2 axis = Vec2::UnitX();  // plane coordinates, unit
  double across = 0;          // the axis line's plane coordinate along axis rotated +90 deg
  double radius = 0;
  double height = 0;          // of the axis line (p . n)
};

// The voxels (but for those the band leaves out) lie on the circle: their rms
// distance to it, weighted by their points, at most this share of r.
constexpr double kMaxCircleResidual = 0.05;
// The second fit takes the voxels within this many rms distances of the first
// circle: an end's rim seen edge-on lies inside the circle, and its voxels'
// normals can be the side's (crease-preserving normals).
constexpr double kCircleBand = 2.5;
// The radius does not change along the axis: K at most half a sphere's.
constexpr double kMaxTaper = 0.5;
// The cylinder rests on the support: its lowest line within this share of r of the plane.
constexpr double kMaxCylinderLift = 0.15;

struct Circle {
  Vec2 centre = Vec2::Zero();  // across the axis, from the segment's centroid
  double radius = 0;
  double rms = 0;              // the points' rms distance to it (algebraic, to first order)
  double turn = 0;             // the axis's turn d (rad), with 5 terms or more
  double taper = 0;            // K, with 6 terms
};

// Kasa's fit over the sums' first `terms` regressors:
// z + g . b = 0 in the least-squares sense, centre (-b0/2, -b1/2), r^2 =
// (b0^2 + b1^2) / 4 - b2; the algebraic residual z + g . b is about 2 r times a
// point's distance to the circle.
std::optional<Circle> fit_circle(const CircleSums& c, Eigen::Index terms) {
  if (c.gg(2, 2) < static_cast<double>(terms)) return std::nullopt;
  const Eigen::MatrixXd gg = c.gg.topLeftCorner(terms, terms).selfadjointView<Eigen::Upper>();
  const Eigen::VectorXd b = gg.ldlt().solve(-c.zg.head(terms));
  const Vec2 centre(-b[0] / 2, -b[1] / 2);
  const double r2 = centre.squaredNorm() - b[2];
  if (!(r2 > 0)) return std::nullopt;
  const double r = std::sqrt(r2), residual = c.zz + b.dot(c.zg.head(terms));
  const double rms = std::sqrt(std::max(0.0, residual) / c.gg(2, 2)) / (2 * r);
  return Circle{centre, r, rms, terms > 3 ? b[3] / 2 : 0.0, terms > 5 ? b[5] : 0.0};
}

// Over the voxels of the segments with a lying axis: the circle sums of the
// voxels of the curved surface that keep(k, q) takes, q their centroids' axis
// coordinates, each weighted by its points. (A voxel's centroid lies inside the
// circle by the sagitta of its chord, v^2 / (8 r): 0.2 mm for 7.5 mm at r = 33 mm.)
template <typename Keep>
std::vector<CircleSums> circle_sums(const SegmentationWork& w, const std::vector<std::uint32_t>& labels,
                                    const std::vector<Principal>& principal, const PlaneFrame& frame,
                                    Eigen::Index terms, Keep&& keep) {
  std::vector<CircleSums> out(principal.size(), CircleSums{terms});
  for_each_segment_voxel(w, labels, [&](std::size_t v, std::size_t k, double n) {
    if (!on_lying_surface(w.normals.directions[v], principal[k])) return;
    const Vec3 q = axis_coordinates(w.grid.centroids[v].cast<double>(), principal[k], frame);
    if (keep(k, q)) out[k].add(q, n);
  });
  return out;
}

// The cylinder of the second fit (the axis turned as it says), if its points
// lie on it, its radius is one along it and it rests on the support.
std::optional<LyingCylinder> resting_cylinder(const Principal& p, const CircleSums& banded, const PlaneFrame& frame) {
  const std::optional<Circle> c = fit_circle(banded, 5), tapered = fit_circle(banded, 6);
  if (!c || c->rms > kMaxCircleResidual * c->radius || !tapered || std::abs(tapered->taper) > kMaxTaper) {
    return std::nullopt;
  }
  const double height = p.centroid.dot(frame.n) + c->centre.y();
  if (std::abs(height - c->radius - frame.height) > kMaxCylinderLift * c->radius) return std::nullopt;
  const Vec3 across = frame.n.cross(p.lying_axis) + c->turn * p.lying_axis;  // x + d t
  const Vec2 side = frame.in_plane(across).normalized(), axis(side.y(), -side.x());
  const Vec3 line = p.centroid + c->centre.x() * across;  // a point of the axis line
  return LyingCylinder{axis, side.dot(frame.in_plane(line)), c->radius, height};
}

// Every segment's cylinder lying on the support, if it is one: a first circle
// over all the voxels of its curved surface, a second over those in the band.
std::vector<std::optional<LyingCylinder>> lying_cylinders(const SegmentationWork& w,
                                                          const std::vector<std::uint32_t>& labels,
                                                          const std::vector<Principal>& principal,
                                                          const PlaneFrame& frame) {
  std::vector<std::optional<LyingCylinder>> out(principal.size());
  if (std::all_of(principal.begin(), principal.end(), [](const Principal& p) { return p.lying_axis.isZero(); })) {
    return out;
  }
  const auto every = [](std::size_t, const Vec3&) { return true; };
  const std::vector<CircleSums> all = circle_sums(w, labels, principal, frame, 3, every);
  std::vector<std::optional<Circle>> first(principal.size());
  for (std::size_t k = 0; k < first.size(); ++k) first[k] = fit_circle(all[k], 3);
  const auto in_band = [&](std::size_t k, const Vec3& q) {
    if (!first[k]) return false;
    return std::abs((q.head<2>() - first[k]->centre).norm() - first[k]->radius) <= kCircleBand * first[k]->rms;
  };
  const std::vector<CircleSums> banded = circle_sums(w, labels, principal, frame, 6, in_band);
  for (std::size_t k = 0; k < out.size(); ++k) {
    if (first[k]) out[k] = resting_cylinder(principal[k], banded[k], frame);
  }
  return out;
}

// The footprint's candidates and heights widened to the whole cylinder: its two
// ends (the candidates' span along the axis), each as wide as the diameter.
void bound_cylinder(const LyingCylinder& cylinder, std::vector<Vec2>& points, Footprint& footprint) {
  double lo = kInf, hi = -kInf;
  for (const Vec2& p : points) lo = std::min(lo, p.dot(cylinder.axis)), hi = std::max(hi, p.dot(cylinder.axis));
  const Vec2 side(-cylinder.axis.y(), cylinder.axis.x());
  for (const double along : {lo, hi}) {
    for (const double offset : {-cylinder.radius, cylinder.radius}) {
      points.push_back(along * cylinder.axis + (cylinder.across + offset) * side);
    }
  }
  footprint.height_lo = std::min(footprint.height_lo, cylinder.height - cylinder.radius);
  footprint.height_hi = std::max(footprint.height_hi, cylinder.height + cylinder.radius);
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
                                       const HullCandidates& candidates,
                                       const std::vector<std::optional<LyingCylinder>>& cylinders) {
  std::vector<OrientedBox> boxes(spreads.size());
  tbb::enumerable_thread_specific<HullScratch> scratch;
  tbb::parallel_for(std::size_t{0}, boxes.size(), [&](std::size_t k) {
    if (!frame) {
      boxes[k] = principal_box(principal[k], spreads[k]);
      return;
    }
    HullScratch& s = scratch.local();
    s.points.assign(candidates[k].begin(), candidates[k].end());
    Footprint footprint = moments[k].footprint;
    const std::optional<LyingCylinder>& cylinder = cylinders[k];
    if (cylinder) bound_cylinder(*cylinder, s.points, footprint);
    detail::convex_hull_into(s.points, s.hull);
    const Rectangle r = cylinder ? rectangle_along(s.hull, cylinder->axis) : min_area_rectangle(s.hull);
    boxes[k] = box_on_plane(r, footprint, *frame);
  });
  return boxes;
}

// --- per segment: normal, grasp -----------------------------------------------------

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
  const std::vector<std::uint32_t> labels = voxel_labels(work, segments);
  const std::vector<NormalMoments> normals = normal_moments(work, labels, K);
  std::vector<Principal> principal(K);
  tbb::parallel_for(std::size_t{0}, K, [&](std::size_t k) {
    principal[k] = principal_frame(moments[k]);
    if (frame) principal[k].lying_axis = lying_axis(moments[k], normals[k], *frame);
  });
  HullCandidates candidates;
  const std::vector<Spread> spreads = segment_spreads(work, segments, principal, moments, frame, candidates);
  const std::vector<std::optional<LyingCylinder>> cylinders =
      frame ? lying_cylinders(work, labels, principal, *frame) : std::vector<std::optional<LyingCylinder>>(K);
  const std::vector<OrientedBox> boxes = segment_boxes(principal, moments, spreads, frame, candidates, cylinders);
  const Vec3 up = frame ? frame->n : Vec3(0, -1, 0);  // without a plane: the sensor's up, -y
  std::vector<SegmentGeometry> out(K);
  tbb::parallel_for(std::size_t{0}, K, [&](std::size_t k) {
    const auto id = static_cast<std::uint32_t>(k + 1);
    out[k] = describe(id, moments[k], principal[k], spreads[k], boxes[k], normals[k].sum, up);
  });
  add_adjacency(work, segments, out);
  return out;
}

}  // namespace lccp
