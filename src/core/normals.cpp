#include "lccp/core/normals.hpp"

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
std::vector<Moments> two_ring_moments(const VoxelGrid& grid, const std::vector<Moments>& own) {
  std::vector<Moments> one_ring(grid.size());
  detail::parallel_for_each_index(grid.size(), [&](std::size_t u) {
    Moments m = 2.0 * own[u];
    for (const std::uint32_t* w = grid.neighbors.begin(u); w != grid.neighbors.end(u); ++w) m += own[*w];
    one_ring[u] = m;
  });
  std::vector<Moments> two_ring(grid.size());
  detail::parallel_for_each_index(grid.size(), [&](std::size_t v) {
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
  return detail::plane_normal(m, toward_sensor).value_or(toward_sensor);
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

}  // namespace

std::vector<Eigen::Vector3f> estimate_voxel_normals(const VoxelGrid& grid) {
  if (!grid.mean_normals.empty()) return given_normals(grid);
  const std::vector<Moments> neighbourhoods = two_ring_moments(grid, centroid_moments(grid));
  std::vector<Eigen::Vector3f> normals(grid.size());
  detail::parallel_for_each_index(grid.size(), [&](std::size_t v) { normals[v] = pca_normal(neighbourhoods[v], grid.centroids[v]); });
  return normals;
}

}  // namespace lccp
