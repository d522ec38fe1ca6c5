#pragma once
// Internal: least-squares plane fitting from accumulated moments (voxel normals).
#include <array>
#include <cstddef>
#include <optional>

#include <Eigen/Core>

namespace lccp::detail {

// Zeroth, first and second moments of a weighted set of points:
// (n, sx, sy, sz, sxx, sxy, sxz, syy, syz, szz).
using Moments = Eigen::Matrix<double, 10, 1>;

// The moments of one point. Inline and element by element (Eigen's comma
// initializer is slow where the two-ring sums call it, once a voxel).
inline Moments moments_of(const Eigen::Vector3f& point) {
  const Eigen::Vector3d c = point.cast<double>();
  Moments m;
  m(0) = 1.0;
  m(1) = c.x();
  m(2) = c.y();
  m(3) = c.z();
  m(4) = c.x() * c.x();
  m(5) = c.x() * c.y();
  m(6) = c.x() * c.z();
  m(7) = c.y() * c.y();
  m(8) = c.y() * c.z();
  m(9) = c.z() * c.z();
  return m;
}

// Element by element, each off-diagonal one computed once and mirrored: the
// same operations as second / n - mean mean^T (a product commutes exactly).
inline Eigen::Matrix3d covariance_of(const Moments& m) {
  const Eigen::Vector3d mean = m.segment<3>(1) / m(0);
  Eigen::Matrix3d c;
  c(0, 0) = m(4) / m(0) - mean(0) * mean(0);
  c(0, 1) = c(1, 0) = m(5) / m(0) - mean(0) * mean(1);
  c(0, 2) = c(2, 0) = m(6) / m(0) - mean(0) * mean(2);
  c(1, 1) = m(7) / m(0) - mean(1) * mean(1);
  c(1, 2) = c(2, 1) = m(8) / m(0) - mean(1) * mean(2);
  c(2, 2) = m(9) / m(0) - mean(2) * mean(2);
  return c;
}

// Unit eigenvector of the smallest eigenvalue of a symmetric positive
// semi-definite 3x3 matrix; empty when that eigenvalue is not simple.
std::optional<Eigen::Vector3d> least_eigenvector(const Eigen::Matrix3d& a);

// least_eigenvector of kSideBySide matrices at once, with the same results: their
// iterations advance side by side, so that one's divisions overlap another's.
constexpr std::size_t kSideBySide = 4;
std::array<std::optional<Eigen::Vector3d>, kSideBySide> least_eigenvectors(
    const std::array<Eigen::Matrix3d, kSideBySide>& a);

// A direction as a float normal, turned to agree with `reference`.
inline Eigen::Vector3f oriented_normal(const Eigen::Vector3d& direction, const Eigen::Vector3f& reference) {
  const Eigen::Vector3f normal = direction.cast<float>();
  return normal.dot(reference) < 0.0f ? Eigen::Vector3f(-normal) : normal;
}

}  // namespace lccp::detail
