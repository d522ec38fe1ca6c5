#pragma once
// Internal: integer grid cells packed into sortable 64-bit keys, and a stable
// radix sort. Shared by voxelization and seeding.
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

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
  std::uint64_t key(const Cell& cell) const {
    const auto c = (cell - origin_).cast<std::uint64_t>();
    return (c.x() * extent_.y() + c.y()) * extent_.z() + c.z();
  }
  // Key difference to the neighbour at (dx, dy, dz); apply with wrap-around arithmetic.
  std::uint64_t offset(int dx, int dy, int dz) const {
    return static_cast<std::uint64_t>((static_cast<std::int64_t>(dx) * extent_.y() + dy) * extent_.z() + dz);
  }
  std::uint64_t row_length() const { return extent_.z(); }
  int key_bits() const { return key_bits_; }

 private:
  Cell origin_;
  Eigen::Array<std::uint64_t, 3, 1> extent_;
  int key_bits_ = 0;
  bool fits_ = true;
};

struct KeyedIndex {
  std::uint64_t key;
  std::uint32_t index;
};

// Stable LSD radix sort on the low `key_bits` bits of the keys: equal keys keep
// their input order, so the result does not depend on threads or timing.
void radix_sort(std::vector<KeyedIndex>& items, int key_bits);

}  // namespace lccp::detail
