#include "lccp/core/normals.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <memory>

#include "parallel.hpp"
#include "plane_fit.hpp"

namespace lccp {
namespace {

using detail::Moments;

// The voxels that the voxels [begin, end) read, themselves and their
// neighbours (ascending rows, VoxelGrid): from `first` to `last`, at most
// `span` consecutive ones at a time for a reader going up the ids.
struct Window {
  std::size_t first;
  std::size_t last;
  std::size_t span;
};

Window window_of(const CompressedRows& neighbors, std::size_t begin, std::size_t end) {
  Window window{begin, begin, 1};
  for (std::size_t v = begin; v < end; ++v) {
    const bool alone = neighbors.count(v) == 0;
    const std::size_t low = alone ? v : std::min<std::size_t>(v, neighbors.begin(v)[0]);
    window.last = std::max({window.last, v, alone ? v : std::size_t{neighbors.end(v)[-1]}});
    window.first = std::min(window.first, low);
    window.span = std::max(window.span, window.last + 1 - low);
  }
  return window;
}

// Moments of a window of consecutive voxels sliding up the ids, in a ring buffer.
class MomentWindow {
 public:
  explicit MomentWindow(std::size_t span) : mask_(std::bit_ceil(span) - 1), slots_(mask_ + 1) {}
  Moments& operator[](std::size_t v) { return slots_[v & mask_]; }

 private:
  std::size_t mask_;
  std::vector<Moments> slots_;
};

// VCCS's neighbourhood: the voxel, then for each u in N[v] (closed) u itself
// and all of N[u]. As sums: m(v) + sum_{u in N[v]} (2 m(u) + sum_{w in N(u)} m(w)).
// The sums of voxels [begin, end) in ascending order, in one pass: each
// voxel's own moments and first ring (the bracket) are computed once, when
// first needed, into windows sliding up the ids, and summed while in cache
// (no array of moments is stored to and read back from memory).
class TwoRings {
 public:
  TwoRings(const VoxelGrid& grid, std::size_t begin, std::size_t end)
      : grid_(grid), rings_(window_of(grid.neighbors, begin, end)),
        owns_(window_of(grid.neighbors, rings_.first, rings_.last + 1)), first_rings_(rings_.span),
        own_(owns_.span), rings_done_(rings_.first), owns_done_(owns_.first) {}

  // The running sums below are locals kept in registers, stored once: SSE
  // stores may alias anything, so a sum stored on every step would make GCC
  // reload the loops' pointers on every step too.
  void sum(std::size_t v, Moments& sum) {
    first_rings_up_to(reach(v));
    Moments m = own_[v];
    m += first_rings_[v];
    for (const std::uint32_t* u = grid_.neighbors.begin(v); u != grid_.neighbors.end(v); ++u) m += first_rings_[*u];
    sum = m;
  }

 private:
  // The highest id among v and its neighbours.
  std::size_t reach(std::size_t v) const {
    return grid_.neighbors.count(v) == 0 ? v : std::max<std::size_t>(v, grid_.neighbors.end(v)[-1]);
  }
  void first_rings_up_to(std::size_t last) {
    for (; rings_done_ <= last; ++rings_done_) {
      const std::size_t u = rings_done_;
      for (; owns_done_ <= reach(u); ++owns_done_) own_[owns_done_] = detail::moments_of(grid_.centroids[owns_done_]);
      Moments m = 2.0 * own_[u];
      for (const std::uint32_t* w = grid_.neighbors.begin(u); w != grid_.neighbors.end(u); ++w) m += own_[*w];
      first_rings_[u] = m;
    }
  }

  const VoxelGrid& grid_;
  const Window rings_, owns_;
  MomentWindow first_rings_, own_;
  std::size_t rings_done_, owns_done_;  // computed up to here
};

// Calls take(v, neighbourhood, covariance, normal) for every voxel with the
// least-variance direction of its neighbourhood's moments, oriented toward the
// sensor at the origin (with fewer than three distinct centroids or a line,
// the direction toward the sensor itself). detail::kSideBySide voxels at a
// time, so that their eigen-solves overlap; each normal is as if solved alone.
template <typename Take>
void for_each_pca_normal(const VoxelGrid& grid, Take take) {
  constexpr std::size_t kGroup = detail::kSideBySide;
  detail::parallel_ranges((grid.size() + kGroup - 1) / kGroup, [&](const auto& groups) {
    TwoRings two_rings(grid, groups.begin() * kGroup, std::min(grid.size(), groups.end() * kGroup));
    for (std::size_t group = groups.begin(); group < groups.end(); ++group) {
      const std::size_t first = group * kGroup, count = std::min(kGroup, grid.size() - first);
      std::array<Moments, kGroup> sums;
      std::array<Eigen::Matrix3d, kGroup> covariances;
      std::fill(covariances.begin() + count, covariances.end(), Eigen::Matrix3d::Zero());  // a last group's spares
      for (std::size_t j = 0; j < count; ++j) {
        two_rings.sum(first + j, sums[j]);
        covariances[j] = detail::covariance_of(sums[j]);
      }
      const auto directions = detail::least_eigenvectors(covariances);
      for (std::size_t j = 0; j < count; ++j) {
        const Eigen::Vector3f toward_sensor = -grid.centroids[first + j].normalized();
        const bool plane = sums[j](0) >= 3.0 && directions[j];  // three points, not a line
        take(first + j, sums[j], covariances[j],
             plane ? detail::oriented_normal(*directions[j], toward_sensor) : toward_sensor);
      }
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
  float tolerance_m;
  float variation;
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
  std::vector<LocalPlane> planes(grid.size());
  for_each_pca_normal(grid, [&](std::size_t v, const Moments& neighbourhood, const Eigen::Matrix3d& covariance,
                                const Eigen::Vector3f& n) { planes[v] = local_plane(neighbourhood, covariance, n); });
  return config.crease_preserving ? crease_preserving(grid, planes, config.planar_variation)
                                  : own_planes(planes, config.planar_variation);
}

}  // namespace lccp
