#pragma once
// Internal: stage 4's settled-once growth (SupervoxelConfig::growth = flood).
#include <cstdint>
#include <vector>

#include "lccp/core/normals.hpp"
#include "lccp/core/supervoxels.hpp"

namespace lccp::detail {

Supervoxels flood_supervoxels(const VoxelGrid& grid, const VoxelNormals& voxel_normals,
                              const std::vector<std::uint32_t>& seeds, const LccpConfig& config);

}  // namespace lccp::detail
