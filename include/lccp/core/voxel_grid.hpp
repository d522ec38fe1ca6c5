#pragma once
// Stage 1 (kStages): voxelization with a 26-neighbourhood (paper A.1, VCCS [15]).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lccp/cloud.hpp"
#include "lccp/config.hpp"

namespace lccp {

inline constexpr std::uint32_t kNoVoxel = 0xffffffffu;

// Compressed sparse rows: the items of row i are items[offsets[i] .. offsets[i+1]).
struct CompressedRows {
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> items;

  std::size_t rows() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  const std::uint32_t* begin(std::size_t row) const { return items.data() + offsets[row]; }
  const std::uint32_t* end(std::size_t row) const { return items.data() + offsets[row + 1]; }
  std::uint32_t count(std::size_t row) const { return offsets[row + 1] - offsets[row]; }
};

// Occupied voxels in ascending order of their integer cell key, which makes
// voxel ids independent of thread count and point order.
struct VoxelGrid {
  std::vector<Eigen::Vector3f> centroids;    // mean of member points (m)
  std::vector<Eigen::Vector3f> colors;       // mean colour, 0..255 per channel (0 if none)
  std::vector<Eigen::Vector3f> mean_normals; // normalized mean of given point normals; empty if none
  CompressedRows points;                     // member point indices per voxel, ascending
  CompressedRows neighbors;                  // 26-neighbourhood, self excluded, ascending
  std::vector<std::uint32_t> voxel_of_point; // per input point; kNoVoxel if not finite
  Binning binning = Binning::euclidean;      // the binning used (automatic resolved)

  std::size_t size() const { return centroids.size(); }
};

// Binning::automatic means camera cells for a cloud, organized or not, whose
// points all lie in a camera's view from the origin (z > 0 and within 60 deg
// of the +z axis, across and up), cubes otherwise. Throws lccp::Error when
// the cloud has no finite point, when camera binning is asked for a point at
// z <= 0, when the cloud spans more cells than the integer keys can hold, or
// when it exceeds a limit (more points or voxels than allowed, a finite point
// beyond max_coordinate_m). Points i with skip[i] != 0 are left out (no voxel),
// as if they were not finite; an empty `skip` leaves none out. A cloud whose
// finite points are all left out gives a grid without voxels. `sensor` sets
// the depth of camera cells beyond z_q (SensorConfig::depth_steps).
VoxelGrid voxelize(const CloudView& cloud, const VoxelConfig& config, const SensorConfig& sensor = {},
                   const LimitsConfig& limits = {}, const std::vector<std::uint8_t>& skip = {});

}  // namespace lccp
