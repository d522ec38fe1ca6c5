#include "lccp/core/normals.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "parallel.hpp"
#include "plane_fit.hpp"

namespace lccp {
namespace {

using detail::Moments;

std::vector<Moments> centroid_moments(const VoxelGrid& grid) {
  std::vector<Moments> moments(grid.size());
  detail::parallel_for_each_index(grid.size(), [&](std::size_t v) { moments[v] = detail::moments_of(grid.centroids[v]); });
  return moments;
}

// VCCS's neighbourhood: the voxel, then for each u in N[v] (closed) u itself
// and all of N[u]. As sums: m(v) + sum_{u in N[v]} (2 m(u) + sum_{w in N(u)} m(w)).
// The sums replace the voxels' own moments in place: the second pass reads only
// a voxel's own, the first pass (which reads its neighbours') is done by then.
std::vector<Moments> two_ring_moments(const VoxelGrid& grid, std::vector<Moments> own) {
  std::vector<Moments> one_ring(grid.size());
  detail::parallel_for_each_index(grid.size(), [&](std::size_t u) {
    Moments m = 2.0 * own[u];
    for (const std::uint32_t* w = grid.neighbors.begin(u); w != grid.neighbors.end(u); ++w) m += own[*w];
    one_ring[u] = m;
  });
  detail::parallel_for_each_index(grid.size(), [&](std::size_t v) {
    Moments m = own[v] + one_ring[v];
    for (const std::uint32_t* u = grid.neighbors.begin(v); u != grid.neighbors.end(v); ++u) m += one_ring[*u];
    own[v] = m;
  });
  return own;
}

// Calls take(v, covariance, normal) for every voxel with the least-variance
// direction of its neighbourhood, oriented toward the sensor at the origin
// (with fewer than three distinct centroids or a line, the direction toward
// the sensor itself). detail::kSideBySide voxels at a time, so that their
// eigen-solves overlap; each normal is as if solved alone.
template <typename Take>
void for_each_pca_normal(const VoxelGrid& grid, const std::vector<Moments>& neighbourhoods, Take take) {
  constexpr std::size_t kGroup = detail::kSideBySide;
  detail::parallel_for_each_index((grid.size() + kGroup - 1) / kGroup, [&](std::size_t group) {
    const std::size_t first = group * kGroup, count = std::min(kGroup, grid.size() - first);
    std::array<Eigen::Matrix3d, kGroup> covariances;
    covariances.fill(Eigen::Matrix3d::Zero());
    for (std::size_t j = 0; j < count; ++j) covariances[j] = detail::covariance_of(neighbourhoods[first + j]);
    const auto directions = detail::least_eigenvectors(covariances);
    for (std::size_t j = 0; j < count; ++j) {
      const Eigen::Vector3f toward_sensor = -grid.centroids[first + j].normalized();
      const bool plane = neighbourhoods[first + j](0) >= 3.0 && directions[j];  // three points, not a line
      take(first + j, covariances[j], plane ? detail::oriented_normal(*directions[j], toward_sensor) : toward_sensor);
    }
  });
}

// Mean point normals as given (multi-view clouds: oriented per view, not
// flipped); voxels without a valid one face the sensor.
std::vector<Eigen::Vector3f> given_normals(const VoxelGrid& grid) {
  std::vector<Eigen::Vector3f> normals = grid.mean_normals;
  detail::parallel_for_each_index(grid.size(), [&](std::size_t v) {
    if (!(normals[v].squaredNorm() > 0.5f)) normals[v] = -grid.centroids[v].normalized();
  });
  return normals;
}

// A neighbourhood's least-squares plane: its centre, its normal, how far from
// it a voxel centroid may lie and still be on it (m), and the variance along
// the normal as a share of the total (the surface variation: 0 on a plane,
// larger across a crease).
struct LocalPlane {
  Eigen::Vector3f centre;
  Eigen::Vector3f normal;
  float tolerance_m = 0;
  float variation = 0;
};

// The tolerance is two standard deviations of the fit, plus 0.1 mm for float
// rounding (the coarsest spacing LimitsConfig allows is 61 um).
LocalPlane local_plane(const Moments& m, const Eigen::Matrix3d& covariance, const Eigen::Vector3f& normal) {
  const Eigen::Vector3d n = normal.cast<double>();
  const double residual = std::max(0.0, n.dot(covariance * n));
  return {(m.segment<3>(1) / m[0]).cast<float>(), normal, 2.0f * std::sqrt(static_cast<float>(residual)) + 1e-4f,
          static_cast<float>(residual / std::max(covariance.trace(), 1e-30))};
}

bool lies_on(const LocalPlane& plane, const Eigen::Vector3f& x) {
  return std::abs(plane.normal.dot(x - plane.centre)) <= plane.tolerance_m;
}

// Crease-preserving normals (a departure from the paper, docs/ARCHITECTURE.md).
// Near a crease a voxel's neighbourhood spans both surfaces and its plane fits
// neither, while some neighbour's neighbourhood lies on one surface only. Each
// voxel takes the plane of the flattest neighbourhood, among its own and its
// neighbours', that its centroid lies on (the first, in neighbour order, of
// equally flat ones), turned toward the sensor. Both tests are evaluated for
// every neighbour and the choice is a select, not a branch: which neighbours
// pass is unpredictable.
VoxelNormals crease_preserving(const VoxelGrid& grid, const std::vector<LocalPlane>& planes, float planar_variation) {
  VoxelNormals result{std::vector<Eigen::Vector3f>(grid.size()), std::vector<std::uint8_t>(grid.size())};
  detail::parallel_for_each_index(grid.size(), [&](std::size_t v) {
    const Eigen::Vector3f& x = grid.centroids[v];
    std::size_t best = v;
    float flattest = planes[v].variation;
    for (const std::uint32_t* u = grid.neighbors.begin(v); u != grid.neighbors.end(v); ++u) {
      const bool flatter = planes[*u].variation < flattest;
      const bool on = lies_on(planes[*u], x);
      const bool better = flatter & on;
      best = better ? *u : best;
      flattest = better ? planes[*u].variation : flattest;
    }
    const Eigen::Vector3f& n = planes[best].normal;
    result.directions[v] = n.dot(x) > 0 ? Eigen::Vector3f(-n) : n;
    result.planar[v] = flattest <= planar_variation;
  });
  return result;
}

// Each voxel's own neighbourhood's plane.
VoxelNormals own_planes(const std::vector<LocalPlane>& planes, float planar_variation) {
  VoxelNormals result{std::vector<Eigen::Vector3f>(planes.size()), std::vector<std::uint8_t>(planes.size())};
  detail::parallel_for_each_index(planes.size(), [&](std::size_t v) {
    result.directions[v] = planes[v].normal;
    result.planar[v] = planes[v].variation <= planar_variation;
  });
  return result;
}

}  // namespace

VoxelNormals estimate_voxel_normals(const VoxelGrid& grid, const NormalConfig& config) {
  if (!grid.mean_normals.empty()) return {given_normals(grid), std::vector<std::uint8_t>(grid.size(), 1)};
  const std::vector<Moments> neighbourhoods = two_ring_moments(grid, centroid_moments(grid));
  std::vector<LocalPlane> planes(grid.size());
  for_each_pca_normal(grid, neighbourhoods, [&](std::size_t v, const Eigen::Matrix3d& covariance, const Eigen::Vector3f& n) {
    planes[v] = local_plane(neighbourhoods[v], covariance, n);
  });
  return config.crease_preserving ? crease_preserving(grid, planes, config.planar_variation)
                                  : own_planes(planes, config.planar_variation);
}

}  // namespace lccp
