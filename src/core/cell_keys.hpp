#pragma once
// Internal: integer grid cells packed into sortable 64-bit keys, and a stable
// radix sort. Shared by voxelization and seeding.
#include <bit>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lccp/core/voxel_grid.hpp"

namespace lccp::detail {

using Cell = Eigen::Array3i;

// Packs cells of a bounding box into keys (x-major, z-minor). The box is padded
// by one cell on every side so that key(c) + offset(dx, dy, dz) is the key of
// the neighbouring cell for |d| <= 1, without wrapping into another row.
class CellKeys {
 public:
  CellKeys(const Cell& min_cell, const Cell& max_cell);

  // False if the padded box has more cells than 64-bit keys can address.
  bool fits() const { return fits_; }
  std::uint64_t key(const Cell& cell) const { return row(cell) * extent_.z() + level(cell); }
  // A cell's (x, y) row of cells, and its place along z within the row:
  // key = row * extent(2) + level.
  std::uint64_t row(const Cell& cell) const {
    const auto c = (cell - origin_).cast<std::uint64_t>();
    return c.x() * extent_.y() + c.y();
  }
  std::uint64_t level(const Cell& cell) const { return static_cast<std::uint64_t>(cell.z() - origin_.z()); }
  // Key difference to the neighbour at (dx, dy, dz); apply with wrap-around arithmetic.
  std::uint64_t offset(int dx, int dy, int dz) const {
    return static_cast<std::uint64_t>((static_cast<std::int64_t>(dx) * extent_.y() + dy) * extent_.z() + dz);
  }
  int key_bits() const { return key_bits_; }
  // Cells along each axis of the padded box (0: x, 1: y, 2: z).
  std::uint64_t extent(int axis) const { return extent_[axis]; }

 private:
  Cell origin_;
  Eigen::Array<std::uint64_t, 3, 1> extent_;
  int key_bits_ = 0;
  bool fits_ = true;
};

// An item's cell key and its index packed into one sortable value,
// key << index_bits | index: sorting by key keeps equal keys in index order.
struct PackedKeys {
  int index_bits = 0;
  int key_bits = 0;

  bool fits() const { return index_bits + key_bits <= 64; }
  std::uint64_t pack(std::uint64_t key, std::uint32_t index) const { return key << index_bits | index; }
  std::uint64_t key(std::uint64_t packed) const { return packed >> index_bits; }
  std::uint32_t index(std::uint64_t packed) const {
    return static_cast<std::uint32_t>(packed & ((std::uint64_t{1} << index_bits) - 1));
  }
};

PackedKeys packed_keys(const CellKeys& keys, std::size_t item_count);

// Runs of equal keys in sorted packed values: each run's key, and its members'
// indices as one row per run, in order.
void group_runs(const std::vector<std::uint64_t>& values, const PackedKeys& packing,
                std::vector<std::uint64_t>& run_keys, CompressedRows& members);

// Stable LSD radix sort on the key bits of packed values, in parallel over
// fixed-size blocks (a stable sort has one result, whatever the threads).
void radix_sort(std::vector<std::uint64_t>& values, const PackedKeys& packing);

}  // namespace lccp::detail
