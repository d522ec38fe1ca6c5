#include "cell_keys.hpp"

#include <cmath>
#include <algorithm>

namespace lccp::detail {

CellKeys::CellKeys(const Cell& min_cell, const Cell& max_cell) : origin_(min_cell - 1) {
  const auto extent = (max_cell - min_cell + 3).cast<std::int64_t>();
  extent_ = extent.cast<std::uint64_t>();
  // Keys must stay below 2^62 so that neighbour offsets never overflow.
  const double cells = static_cast<double>(extent.x()) * static_cast<double>(extent.y()) *
                       static_cast<double>(extent.z());
  fits_ = cells < std::ldexp(1.0, 62);
  if (fits_) {
    key_bits_ = std::bit_width(extent_.x() * extent_.y() * extent_.z() - 1);
  }
}

void radix_sort(std::vector<KeyedIndex>& items, int key_bits) {
  // As few passes as possible with digits of at most 12 bits (counts stay in L1).
  constexpr int kMaxDigitBits = 12;
  const int passes = (key_bits + kMaxDigitBits - 1) / kMaxDigitBits;
  if (passes == 0) return;
  const int digit_bits = (key_bits + passes - 1) / passes;
  const std::uint64_t mask = (std::uint64_t{1} << digit_bits) - 1;
  std::vector<KeyedIndex> buffer(items.size());
  std::vector<std::uint32_t> counts(std::size_t{1} << digit_bits);
  for (int shift = 0; shift < key_bits; shift += digit_bits) {
    std::fill(counts.begin(), counts.end(), 0u);
    for (const auto& item : items) ++counts[(item.key >> shift) & mask];
    std::uint32_t running = 0;
    for (auto& count : counts) {
      const std::uint32_t c = count;
      count = running;
      running += c;
    }
    for (const auto& item : items) buffer[counts[(item.key >> shift) & mask]++] = item;
    items.swap(buffer);
  }
}

}  // namespace lccp::detail
