#pragma once
// Internal: the owners (supervoxels, patches) of a voxel's neighbours, as
// growth, its refinement and the adjacency graph gather them.
#include <array>
#include <cstddef>
#include <cstdint>

#include "lccp/core/voxel_grid.hpp"

namespace lccp::detail {

inline constexpr std::uint32_t kFree = 0xffffffffu;

// Writes to `out` the owner of each neighbour w of voxel v that accept(w, owner)
// takes, a repeat of the previous one written dropped (neighbours of one owner
// come in runs: ids are x-major), and returns how many it wrote. Free of
// branches: which neighbours qualify is unpredictable at boundaries, where
// branches mispredict. An owner of kFree (no owner yet) is never written.
template <typename Accept>
std::size_t neighbour_owners(const CompressedRows& neighbors, std::size_t v, const std::uint32_t* owner, Accept accept,
                             std::array<std::uint32_t, 26>& out) {
  std::size_t count = 0;
  std::uint32_t last = kFree;
  for (const std::uint32_t* w = neighbors.begin(v); w != neighbors.end(v); ++w) {
    const std::uint32_t k = owner[*w];
    const bool kept = accept(*w, k) & (k != kFree) & (k != last);
    out[count] = k;
    count += kept;
    last = kept ? k : last;
  }
  return count;
}

}  // namespace lccp::detail
