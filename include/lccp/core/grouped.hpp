#pragma once
// Items grouped by a key 0..K-1 with a counting sort: K groups cost two arrays,
// not K allocations (the stages after growth, where K is the frame's segments).
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

namespace lccp {

// Group k's items are items[offsets[k] .. offsets[k + 1]), in the order they came.
template <typename T>
struct Grouped {
  std::vector<std::uint32_t> offsets;
  std::vector<T> items;

  std::size_t size() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::span<const T> operator[](std::size_t k) const {
    return {items.data() + offsets[k], items.data() + offsets[k + 1]};
  }
};

// each(emit) calls emit(key, item), key < K, for every item, the same items in
// the same order each time: it is called twice, to count and to fill.
template <typename T, typename Each>
Grouped<T> group_by_key(std::size_t K, Each&& each) {
  Grouped<T> g;
  g.offsets.assign(K + 1, 0);
  each([&](std::uint32_t key, const T&) { ++g.offsets[key + 1]; });
  std::partial_sum(g.offsets.begin(), g.offsets.end(), g.offsets.begin());
  g.items.resize(g.offsets.back());
  std::vector<std::uint32_t> next(g.offsets.begin(), g.offsets.end() - 1);
  each([&](std::uint32_t key, const T& item) { g.items[next[key]++] = item; });
  return g;
}

}  // namespace lccp
