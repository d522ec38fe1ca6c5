#include "lccp/core/adjacency.hpp"

#include <algorithm>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_sort.h>

#include "parallel.hpp"

namespace lccp {

std::vector<Edge> supervoxel_adjacency(const VoxelGrid& grid, const Supervoxels& supervoxels) {
  const auto& supervoxel_of_voxel = supervoxels.supervoxel_of_voxel;
  const auto& absorbed = supervoxels.absorbed;
  // Each thread collects (a, b) pairs, a < b, packed into 64 bits.
  tbb::enumerable_thread_specific<std::vector<std::uint64_t>> local_pairs;
  detail::parallel_ranges(grid.size(), [&](const auto& range) {
    auto& pairs = local_pairs.local();
    for (std::size_t v = range.begin(); v < range.end(); ++v) {
      if (absorbed[v]) continue;
      const std::uint64_t a = supervoxel_of_voxel[v];
      const std::size_t first_of_voxel = pairs.size();
      for (const std::uint32_t* w = grid.neighbors.begin(v); w != grid.neighbors.end(v); ++w) {
        const std::uint64_t pair = a << 32 | supervoxel_of_voxel[*w];
        if (supervoxel_of_voxel[*w] > a && !absorbed[*w] && std::find(pairs.begin() + first_of_voxel, pairs.end(), pair) == pairs.end()) {
          pairs.push_back(pair);
        }
      }
    }
  });
  std::vector<std::uint64_t> pairs;
  for (const auto& local : local_pairs) pairs.insert(pairs.end(), local.begin(), local.end());
  tbb::parallel_sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());

  std::vector<Edge> edges(pairs.size());
  std::transform(pairs.begin(), pairs.end(), edges.begin(), [](std::uint64_t p) {
    return Edge{static_cast<std::uint32_t>(p >> 32), static_cast<std::uint32_t>(p)};
  });
  return edges;
}

}  // namespace lccp
