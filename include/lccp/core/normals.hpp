#pragma once
// Stage 2 (kStages): one unit normal per voxel.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lccp/config.hpp"
#include "lccp/core/voxel_grid.hpp"

namespace lccp {

// PCA over the voxel centroids of the 2-ring neighbourhood (each centroid
// weighted by the number of paths of length <= 2 reaching it, as VCCS does),
// flipped toward the sensor at the origin. Voxels whose neighbourhood is
// degenerate get the direction toward the sensor. If the grid carries mean
// point normals (merged multi-view clouds, paper Fig. 3) those are used instead.
// With config.crease_preserving (beyond the paper), a voxel whose own
// neighbourhood straddles a crease takes the plane of the flattest neighbouring
// neighbourhood it lies on instead: normals do not blend across the crease.
// Given point normals are all planar.
struct VoxelNormals {
  std::vector<Eigen::Vector3f> directions;  // one unit normal per voxel
  // Per voxel, 1 if its normal is a plane's: the neighbourhood it came from
  // has a surface variation (Pauly, Gross and Kobbelt 2002: the least
  // eigenvalue's share of the covariance's trace) of at most
  // NormalConfig::planar_variation; 0 across a crease or a step.
  std::vector<std::uint8_t> planar;

  std::size_t size() const { return directions.size(); }
};

VoxelNormals estimate_voxel_normals(const VoxelGrid& grid, const NormalConfig& config);

}  // namespace lccp
