#pragma once
// Convex hulls in a plane's coordinates, for the footprints of segments on the
// support plane (geometry.cpp: boxes; grouping.cpp: what stands inside what;
// occlusion.cpp: the face two tops would make).
#include <algorithm>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lccp/core/grouped.hpp"

namespace lccp::detail {

// Plane coordinates: a right-handed frame (e1, e2, n) on the plane normal n.
struct InPlane {
  Eigen::Vector3d e1, e2;
  explicit InPlane(const Eigen::Vector3d& n) {
    Eigen::Index least = 0;
    n.cwiseAbs().minCoeff(&least);
    e1 = n.cross(Eigen::Vector3d::Unit(least)).normalized();
    e2 = n.cross(e1);
  }
  Eigen::Vector2d operator()(const Eigen::Vector3d& p) const { return {p.dot(e1), p.dot(e2)}; }
};

// > 0 when o, a, b turn counter-clockwise.
inline double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Andrew's monotone chain (A. M. Andrew, "Another efficient algorithm for convex
// hulls in two dimensions", Inf. Process. Lett. 9(5), 1979): the hull vertices of
// p counter-clockwise into `hull`, without collinear ones; one or two points for
// degenerate sets. p is sorted and deduplicated in place; both keep their
// capacity, so a caller that reuses them allocates nothing once they are large enough.
inline void convex_hull_into(std::vector<Eigen::Vector2d>& p, std::vector<Eigen::Vector2d>& hull) {
  const auto lexicographic = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y();
  };
  std::sort(p.begin(), p.end(), lexicographic);
  p.erase(std::unique(p.begin(), p.end()), p.end());
  hull.resize(p.size() < 3 ? p.size() : 2 * p.size());
  if (p.size() < 3) {
    std::copy(p.begin(), p.end(), hull.begin());
    return;
  }
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {  // lower hull
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {  // upper hull
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);  // the last point is the first
}

// The hull of each group, the hulls one after another in one array; two
// buffers reused for all of them.
inline Grouped<Eigen::Vector2d> hulls_of(const Grouped<Eigen::Vector2d>& groups) {
  Grouped<Eigen::Vector2d> hulls;
  hulls.offsets.reserve(groups.size() + 1);
  hulls.offsets.push_back(0);
  std::vector<Eigen::Vector2d> points, hull;
  for (std::size_t k = 0; k < groups.size(); ++k) {
    points.assign(groups[k].begin(), groups[k].end());
    convex_hull_into(points, hull);
    hulls.items.insert(hulls.items.end(), hull.begin(), hull.end());
    hulls.offsets.push_back(static_cast<std::uint32_t>(hulls.items.size()));
  }
  return hulls;
}

// Whether q lies inside (or on) the counter-clockwise convex polygon `hull`,
// or within `margin` outside each of its edges' lines; never for a hull of
// fewer than three vertices.
inline bool inside_hull(std::span<const Eigen::Vector2d> hull, const Eigen::Vector2d& q, double margin = 0.0) {
  if (hull.size() < 3) return false;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d& a = hull[i];
    const Eigen::Vector2d& b = hull[(i + 1) % hull.size()];
    if (cross(a, b, q) < -margin * (b - a).norm()) return false;
  }
  return true;
}

}  // namespace lccp::detail
