#include "plane_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>

namespace lccp::detail {
namespace {

// Smallest eigenvalues of N symmetric positive semi-definite 3x3 matrices:
// Halley's method on each characteristic cubic p(l) = l^3 - c2 l^2 + c1 l - c0
// from l = 0. p is increasing and concave on [0, l_min], where Halley's step
// is shorter than Newton's, so the iterates rise monotonically to l_min
// without overshooting, converging cubically (no trigonometry needed).
// Each matrix gets exactly the iterates it would get alone; they advance side
// by side only so that their divisions overlap, and a finished one stands still.
template <std::size_t N>
std::array<double, N> smallest_eigenvalues(const std::array<Eigen::Matrix3d, N>& a) {
  double c2[N], c1[N], c0[N], l[N];
  bool moving[N];
  for (std::size_t j = 0; j < N; ++j) {
    c2[j] = a[j].trace();
    c1[j] = a[j](0, 0) * a[j](1, 1) + a[j](0, 0) * a[j](2, 2) + a[j](1, 1) * a[j](2, 2) - a[j](0, 1) * a[j](0, 1) -
            a[j](0, 2) * a[j](0, 2) - a[j](1, 2) * a[j](1, 2);
    c0[j] = a[j].determinant();
    l[j] = 0.0;
    moving[j] = true;
  }
  for (int i = 0; i < 32 && std::find(moving, moving + N, true) != moving + N; ++i) {
    for (std::size_t j = 0; j < N; ++j) {
      const double p = ((l[j] - c2[j]) * l[j] + c1[j]) * l[j] - c0[j];
      const double slope = (3.0 * l[j] - 2.0 * c2[j]) * l[j] + c1[j];
      const double curvature = 6.0 * l[j] - 2.0 * c2[j];
      const double denominator = 2.0 * slope * slope - p * curvature;
      const bool steps = moving[j] & (slope > 0.0) & (denominator > 0.0);
      const double step = -2.0 * p * slope / denominator;
      l[j] = steps ? l[j] + step : l[j];
      moving[j] = steps & (step > 1e-12 * c2[j]);
    }
  }
  std::array<double, N> result;
  std::copy(l, l + N, result.begin());
  return result;
}

// Unit eigenvector of eigenvalue l_min: the widest cross product of two rows
// of A - l_min I. Empty when that eigenvalue is not simple (a line or a blob).
std::optional<Eigen::Vector3d> eigenvector_of(const Eigen::Matrix3d& a, double l_min) {
  const Eigen::Matrix3d b = a - l_min * Eigen::Matrix3d::Identity();
  const std::array<Eigen::Vector3d, 3> candidates{b.row(0).cross(b.row(1)), b.row(0).cross(b.row(2)),
                                                  b.row(1).cross(b.row(2))};
  const std::array<double, 3> widths{candidates[0].squaredNorm(), candidates[1].squaredNorm(),
                                     candidates[2].squaredNorm()};
  const std::size_t widest = std::max_element(widths.begin(), widths.end()) - widths.begin();  // the first of equals
  const double scale = b.squaredNorm();
  if (!(widths[widest] > 1e-12 * scale * scale)) return std::nullopt;
  return Eigen::Vector3d(candidates[widest] / std::sqrt(widths[widest]));  // as Eigen's normalized()
}

}  // namespace

std::optional<Eigen::Vector3d> least_eigenvector(const Eigen::Matrix3d& a) {
  return eigenvector_of(a, smallest_eigenvalues<1>({a})[0]);
}

std::array<std::optional<Eigen::Vector3d>, kSideBySide> least_eigenvectors(
    const std::array<Eigen::Matrix3d, kSideBySide>& a) {
  const std::array<double, kSideBySide> l_min = smallest_eigenvalues(a);
  std::array<std::optional<Eigen::Vector3d>, kSideBySide> result;
  for (std::size_t j = 0; j < kSideBySide; ++j) result[j] = eigenvector_of(a[j], l_min[j]);
  return result;
}

}  // namespace lccp::detail
