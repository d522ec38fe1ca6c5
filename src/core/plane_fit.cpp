#include "plane_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>

namespace lccp::detail {
namespace {

// Smallest eigenvalue of a symmetric positive semi-definite 3x3 matrix:
// Halley's method on its characteristic cubic p(l) = l^3 - c2 l^2 + c1 l - c0
// from l = 0. p is increasing and concave on [0, l_min], where Halley's step
// is shorter than Newton's, so the iterates rise monotonically to l_min
// without overshooting, converging cubically (no trigonometry needed).
double smallest_eigenvalue(const Eigen::Matrix3d& a) {
  const double c2 = a.trace();
  const double c1 = a(0, 0) * a(1, 1) + a(0, 0) * a(2, 2) + a(1, 1) * a(2, 2) - a(0, 1) * a(0, 1) -
                    a(0, 2) * a(0, 2) - a(1, 2) * a(1, 2);
  const double c0 = a.determinant();
  double l = 0.0;
  for (int i = 0; i < 32; ++i) {
    const double p = ((l - c2) * l + c1) * l - c0;
    const double slope = (3.0 * l - 2.0 * c2) * l + c1;
    const double curvature = 6.0 * l - 2.0 * c2;
    const double denominator = 2.0 * slope * slope - p * curvature;
    if (!(slope > 0.0) || !(denominator > 0.0)) break;
    const double step = -2.0 * p * slope / denominator;
    l += step;
    if (!(step > 1e-12 * c2)) break;
  }
  return l;
}

}  // namespace

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

std::optional<Eigen::Vector3f> plane_normal(double count, const Eigen::Matrix3d& covariance,
                                            const Eigen::Vector3f& reference) {
  const auto direction = count >= 3.0 ? least_eigenvector(covariance) : std::nullopt;
  if (!direction) return std::nullopt;
  const Eigen::Vector3f normal = direction->cast<float>();
  return normal.dot(reference) < 0.0f ? Eigen::Vector3f(-normal) : normal;
}

}  // namespace lccp::detail
