#include "lccp/core/normals.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace lccp {
namespace {

// Zeroth, first and second moments of a weighted set of centroids:
// (n, sx, sy, sz, sxx, sxy, sxz, syy, syz, szz).
using Moments = Eigen::Matrix<double, 10, 1>;

Moments moments_of(const Eigen::Vector3f& point) {
  const Eigen::Vector3d c = point.cast<double>();
  Moments m;
  m << 1.0, c.x(), c.y(), c.z(), c.x() * c.x(), c.x() * c.y(), c.x() * c.z(), c.y() * c.y(), c.y() * c.z(),
      c.z() * c.z();
  return m;
}

Eigen::Matrix3d covariance_of(const Moments& m) {
  const Eigen::Vector3d mean = m.segment<3>(1) / m(0);
  Eigen::Matrix3d second;
  second << m(4), m(5), m(6), m(5), m(7), m(8), m(6), m(8), m(9);
  return second / m(0) - mean * mean.transpose();
}

// Smallest eigenvalue of a symmetric positive semi-definite 3x3 matrix:
// Newton on its characteristic cubic p(l) = l^3 - c2 l^2 + c1 l - c0 from
// l = 0. p is increasing and concave on [0, l_min], so the iterates rise
// monotonically to l_min without overshooting (no trigonometry needed).
double smallest_eigenvalue(const Eigen::Matrix3d& a) {
  const double c2 = a.trace();
  const double c1 = a(0, 0) * a(1, 1) + a(0, 0) * a(2, 2) + a(1, 1) * a(2, 2) - a(0, 1) * a(0, 1) -
                    a(0, 2) * a(0, 2) - a(1, 2) * a(1, 2);
  const double c0 = a.determinant();
  double l = 0.0;
  for (int i = 0; i < 32; ++i) {
    const double p = ((l - c2) * l + c1) * l - c0;
    const double slope = (3.0 * l - 2.0 * c2) * l + c1;
    if (!(slope > 0.0)) break;
    const double step = -p / slope;
    l += step;
    if (!(step > 1e-12 * c2)) break;
  }
  return l;
}

// Unit eigenvector of the smallest eigenvalue: the widest cross product of two
// rows of A - l_min I. Empty when that eigenvalue is not simple (a line or a blob).
std::optional<Eigen::Vector3d> least_eigenvector(const Eigen::Matrix3d& a) {
  const Eigen::Matrix3d b = a - smallest_eigenvalue(a) * Eigen::Matrix3d::Identity();
  const std::array<Eigen::Vector3d, 3> candidates{b.row(0).cross(b.row(1)), b.row(0).cross(b.row(2)),
                                                  b.row(1).cross(b.row(2))};
  const auto widest = std::max_element(candidates.begin(), candidates.end(),
                                       [](const auto& x, const auto& y) { return x.squaredNorm() < y.squaredNorm(); });
  const double scale = b.squaredNorm();
  if (!(widest->squaredNorm() > 1e-12 * scale * scale)) return std::nullopt;
  return widest->normalized();
}

template <typename Body>
void for_each_voxel(std::size_t n, Body body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const auto& range) {
    for (std::size_t v = range.begin(); v < range.end(); ++v) body(v);
  });
}

std::vector<Moments> centroid_moments(const VoxelGrid& grid) {
  std::vector<Moments> moments(grid.size());
  for_each_voxel(grid.size(), [&](std::size_t v) { moments[v] = moments_of(grid.centroids[v]); });
  return moments;
}

// VCCS's neighbourhood: the voxel, then for each u in N[v] (closed) u itself
// and all of N[u]. As sums: m(v) + sum_{u in N[v]} (2 m(u) + sum_{w in N(u)} m(w)).
std::vector<Moments> two_ring_moments(const VoxelGrid& grid, const std::vector<Moments>& own) {
  std::vector<Moments> one_ring(grid.size());
  for_each_voxel(grid.size(), [&](std::size_t u) {
    Moments m = 2.0 * own[u];
    for (const std::uint32_t* w = grid.neighbors.begin(u); w != grid.neighbors.end(u); ++w) m += own[*w];
    one_ring[u] = m;
  });
  std::vector<Moments> two_ring(grid.size());
  for_each_voxel(grid.size(), [&](std::size_t v) {
    Moments m = own[v] + one_ring[v];
    for (const std::uint32_t* u = grid.neighbors.begin(v); u != grid.neighbors.end(v); ++u) m += one_ring[*u];
    two_ring[v] = m;
  });
  return two_ring;
}

// Least-variance direction of the neighbourhood, oriented toward the sensor at
// the origin; with fewer than three distinct centroids or a line, the direction
// toward the sensor itself.
Eigen::Vector3f pca_normal(const Moments& m, const Eigen::Vector3f& centroid) {
  const Eigen::Vector3f toward_sensor = -centroid.normalized();
  const auto direction = m(0) >= 3.0 ? least_eigenvector(covariance_of(m)) : std::nullopt;
  if (!direction) return toward_sensor;
  const Eigen::Vector3f normal = direction->cast<float>();
  return normal.dot(toward_sensor) < 0.0f ? Eigen::Vector3f(-normal) : normal;
}

// Mean point normals as given (multi-view clouds: oriented per view, not
// flipped); voxels without a valid one face the sensor.
std::vector<Eigen::Vector3f> given_normals(const VoxelGrid& grid) {
  std::vector<Eigen::Vector3f> normals = grid.mean_normals;
  for_each_voxel(grid.size(), [&](std::size_t v) {
    if (!(normals[v].squaredNorm() > 0.5f)) normals[v] = -grid.centroids[v].normalized();
  });
  return normals;
}

}  // namespace

std::vector<Eigen::Vector3f> estimate_voxel_normals(const VoxelGrid& grid) {
  if (!grid.mean_normals.empty()) return given_normals(grid);
  const std::vector<Moments> neighbourhoods = two_ring_moments(grid, centroid_moments(grid));
  std::vector<Eigen::Vector3f> normals(grid.size());
  for_each_voxel(grid.size(), [&](std::size_t v) { normals[v] = pca_normal(neighbourhoods[v], grid.centroids[v]); });
  return normals;
}

}  // namespace lccp
