#include "lccp/core/adjacency.hpp"

#include <algorithm>
#include <array>
#include <bit>

#include <tbb/enumerable_thread_specific.h>

#include "cell_keys.hpp"
#include "neighbour_owners.hpp"
#include "parallel.hpp"

namespace lccp {

std::vector<Edge> supervoxel_adjacency(const VoxelGrid& grid, const Supervoxels& supervoxels) {
  const auto& supervoxel_of = supervoxels.supervoxel_of_voxel;
  const auto& absorbed = supervoxels.absorbed;
  const int id_bits = std::max(1, static_cast<int>(std::bit_width(supervoxels.size())));
  // Each thread collects pairs a < b packed as a << id_bits | b, once per voxel.
  tbb::enumerable_thread_specific<std::vector<std::uint64_t>> local_pairs;
  detail::parallel_ranges(grid.size(), [&](const auto& range) {
    auto& pairs = local_pairs.local();
    for (std::size_t v = range.begin(); v < range.end(); ++v) {
      if (absorbed[v]) continue;
      // The neighbours' larger ids (absorbed voxels left out).
      const std::uint32_t a = supervoxel_of[v];
      std::array<std::uint32_t, 26> larger;
      const std::size_t count = detail::neighbour_owners(
          grid.neighbors, v, supervoxel_of.data(),
          [&](std::uint32_t w, std::uint32_t b) { return (b > a) & (absorbed[w] == 0); }, larger);
      const auto first_of_voxel = static_cast<std::ptrdiff_t>(pairs.size());
      for (std::size_t i = 0; i < count; ++i) {
        const std::uint64_t pair = std::uint64_t{a} << id_bits | larger[i];
        if (std::find(pairs.begin() + first_of_voxel, pairs.end(), pair) == pairs.end()) pairs.push_back(pair);
      }
    }
  });
  std::vector<std::uint64_t> pairs;
  for (const auto& local : local_pairs) pairs.insert(pairs.end(), local.begin(), local.end());
  detail::radix_sort(pairs, detail::PackedKeys{0, 2 * id_bits});
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());

  std::vector<Edge> edges(pairs.size());
  const std::uint64_t mask = (std::uint64_t{1} << id_bits) - 1;
  std::transform(pairs.begin(), pairs.end(), edges.begin(), [&](std::uint64_t p) {
    return Edge{static_cast<std::uint32_t>(p >> id_bits), static_cast<std::uint32_t>(p & mask)};
  });
  return edges;
}

}  // namespace lccp
