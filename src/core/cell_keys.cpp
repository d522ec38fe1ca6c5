#include "cell_keys.hpp"

#include <cmath>
#include <algorithm>
#include <limits>

#include <tbb/parallel_for.h>

namespace lccp::detail {

CellKeys::CellKeys(const Cell& min_cell, const Cell& max_cell) {
  // In 64 bits: the span of two ints does not fit in an int.
  const Eigen::Array3<std::int64_t> low = min_cell.cast<std::int64_t>() - 1;
  const Eigen::Array3<std::int64_t> extent = max_cell.cast<std::int64_t>() - low + 2;
  // Cell - origin is taken in int, so each side must fit one; keys must stay
  // below 2^62 so that neighbour offsets never overflow.
  const double cells = static_cast<double>(extent.x()) * static_cast<double>(extent.y()) *
                       static_cast<double>(extent.z());
  fits_ = (extent > 0).all() && (low >= std::numeric_limits<int>::min()).all() &&
          (extent < std::numeric_limits<int>::max()).all() && cells < std::ldexp(1.0, 62);
  if (!fits_) return;
  origin_ = low.cast<int>();
  extent_ = extent.cast<std::uint64_t>();
  key_bits_ = std::bit_width(extent_.x() * extent_.y() * extent_.z() - 1);
}

PackedKeys packed_keys(const CellKeys& keys, std::size_t item_count) {
  return {std::max(1, static_cast<int>(std::bit_width(item_count))), keys.key_bits()};
}

void group_runs(const std::vector<std::uint64_t>& values, const PackedKeys& packing,
                std::vector<std::uint64_t>& run_keys, CompressedRows& members) {
  run_keys.clear();
  members.items.resize(values.size());
  members.offsets.clear();
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::uint64_t key = packing.key(values[i]);
    if (run_keys.empty() || key != run_keys.back()) {
      run_keys.push_back(key);
      members.offsets.push_back(static_cast<std::uint32_t>(i));
    }
    members.items[i] = packing.index(values[i]);
  }
  members.offsets.push_back(static_cast<std::uint32_t>(values.size()));
}

void radix_sort(std::vector<std::uint64_t>& values, const PackedKeys& packing) {
  // As few passes as possible with digits of at most 12 bits (counts stay in L1).
  constexpr int kMaxDigitBits = 12;
  constexpr std::size_t kBlock = std::size_t{1} << 14;
  const int passes = (packing.key_bits + kMaxDigitBits - 1) / kMaxDigitBits;
  if (passes == 0 || values.size() < 2) return;
  const int digit_bits = (packing.key_bits + passes - 1) / passes;
  const std::size_t buckets = std::size_t{1} << digit_bits;
  const std::size_t blocks = (values.size() + kBlock - 1) / kBlock;
  std::vector<std::uint64_t> buffer(values.size());
  std::vector<std::uint32_t> offsets(blocks * buckets);  // per block, per digit
  for (int pass = 0; pass < passes; ++pass) {
    const int shift = packing.index_bits + pass * digit_bits;
    const auto digit = [&](std::uint64_t v) { return (v >> shift) & (buckets - 1); };
    tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
      std::uint32_t* count = offsets.data() + b * buckets;
      std::fill(count, count + buckets, 0u);
      for (std::size_t i = b * kBlock; i < std::min(values.size(), (b + 1) * kBlock); ++i) ++count[digit(values[i])];
    });
    // Exclusive prefix in (digit, block) order keeps the sort stable.
    std::uint32_t running = 0;
    for (std::size_t d = 0; d < buckets; ++d) {
      for (std::size_t b = 0; b < blocks; ++b) {
        const std::uint32_t c = offsets[b * buckets + d];
        offsets[b * buckets + d] = running;
        running += c;
      }
    }
    tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
      std::uint32_t* next = offsets.data() + b * buckets;
      for (std::size_t i = b * kBlock; i < std::min(values.size(), (b + 1) * kBlock); ++i) {
        buffer[next[digit(values[i])]++] = values[i];
      }
    });
    values.swap(buffer);
  }
}

}  // namespace lccp::detail
