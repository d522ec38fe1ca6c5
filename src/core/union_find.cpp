#include "lccp/core/union_find.hpp"

#include <utility>

namespace lccp {

ConcurrentUnionFind::ConcurrentUnionFind(std::uint32_t size)
    : size_(size), parent_(std::make_unique<std::atomic<std::uint32_t>[]>(size)) {
  for (std::uint32_t i = 0; i < size; ++i) parent_[i].store(i, std::memory_order_relaxed);
}

// Invariant: parent[x] <= x, and a parent only ever moves to a smaller ancestor,
// so halving with a failed compare-exchange is harmless.
std::uint32_t ConcurrentUnionFind::find(std::uint32_t x) {
  for (;;) {
    std::uint32_t parent = parent_[x].load(std::memory_order_acquire);
    if (parent == x) return x;
    const std::uint32_t grandparent = parent_[parent].load(std::memory_order_acquire);
    if (parent != grandparent) {
      parent_[x].compare_exchange_weak(parent, grandparent, std::memory_order_acq_rel, std::memory_order_acquire);
    }
    x = grandparent;
  }
}

void ConcurrentUnionFind::unite(std::uint32_t a, std::uint32_t b) {
  for (;;) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (a < b) std::swap(a, b);
    // Link the larger root under the smaller one; retry if a was linked meanwhile.
    std::uint32_t expected = a;
    if (parent_[a].compare_exchange_strong(expected, b, std::memory_order_acq_rel, std::memory_order_acquire)) return;
  }
}

}  // namespace lccp
