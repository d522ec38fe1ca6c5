#pragma once
// Stages 3-4 (kStages): VCCS supervoxels, seeded on a grid and grown over voxel adjacency.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lccp/config.hpp"
#include "lccp/core/normals.hpp"
#include "lccp/core/voxel_grid.hpp"

namespace lccp {

// Voxels that seed a supervoxel: per occupied cell of the seed grid (spacing
// seed_size_m; with depth_scaled_seeds and camera cells, 4 cells beyond
// z0 = s / (4 v)), the voxel nearest the cell centre, kept if enough voxels lie
// within half a spacing of it. Ascending voxel ids.
std::vector<std::uint32_t> select_seeds(const VoxelGrid& grid, const SupervoxelConfig& config,
                                        float voxel_size_m);

struct Supervoxels {
  std::vector<std::uint32_t> supervoxel_of_voxel;  // every voxel has one
  std::vector<std::uint8_t> absorbed;              // per voxel: 1 if it joined after growth (label only)
  std::vector<Eigen::Vector3f> centroids;          // mean of grown member voxel centroids (m)
  std::vector<Eigen::Vector3f> normals;            // normalized sum of grown member voxel normals
  std::vector<Eigen::Vector3f> colors;             // mean grown member voxel colour
  std::vector<std::uint32_t> voxel_counts;         // grown members

  std::size_t size() const { return centroids.size(); }
};

// Patches grown from the seeds, as config.supervoxels.growth says.
//
// flood (the default): the seeds' patches flood the voxel adjacency together,
// a free voxel joining the patch nearest to it by the VCCS distance below, to
// the patch's mean as it stands; each voxel settles once. A patch admits only
// voxels within max_normal_angle_deg of its normal, within the sensor's depth
// tolerance of its plane (SensorConfig) and within 1.8 s of its centre, so it
// never holds two surfaces meeting at a crease or a step; voxels no seed's
// patch admits seed patches of their own, in voxel order. Then one VCCS pass:
// each voxel moves to the admitting neighbouring patch nearest to it.
// Supervoxels are the patches' member means, their normals those of their
// planar members (VoxelNormals::planar); every voxel is a member (none absorbed).
//
// vccs: flow-constrained growth, int(1.8 s / v) - 1 synchronous passes in which every
// voxel joins the neighbouring supervoxel with the smallest distance
// D = w_n (1 - |n1.n2|) + w_c |drgb| / 255 + w_s |dx| / s (s: the seed spacing
// at the supervoxel centre's depth), then centroids are
// recomputed; a voxel changes owner only for a distance below the one at which
// it was claimed (VCCS). Voxels no supervoxel reached are absorbed: they take
// the nearest neighbouring supervoxel's label but do not shape it or its
// adjacency. Components without any seed become supervoxels of their own.
Supervoxels grow_supervoxels(const VoxelGrid& grid, const VoxelNormals& voxel_normals,
                             const std::vector<std::uint32_t>& seeds, const LccpConfig& config);

}  // namespace lccp
