#pragma once
// Stage 5 (kStages): the supervoxel adjacency graph G(V, E) (paper A.1).
#include <cstdint>
#include <vector>

#include "lccp/core/supervoxels.hpp"
#include "lccp/core/voxel_grid.hpp"

namespace lccp {

struct Edge {
  std::uint32_t a = 0;  // a < b
  std::uint32_t b = 0;
  friend bool operator==(const Edge&, const Edge&) = default;
};

// Two supervoxels are adjacent when any of their grown (not absorbed) voxels
// are. Sorted, unique.
std::vector<Edge> supervoxel_adjacency(const VoxelGrid& grid, const Supervoxels& supervoxels);

}  // namespace lccp
