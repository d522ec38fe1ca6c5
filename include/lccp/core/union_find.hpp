#pragma once
// Lock-free union-find for connected components over convex edges.
#include <atomic>
#include <cstdint>
#include <memory>

namespace lccp {

// unite() may be called from many threads at once. Roots are always the
// smallest element of their set (links go from the larger root to the smaller),
// so the final partition and its representatives do not depend on the order
// or interleaving of the unions.
class ConcurrentUnionFind {
 public:
  explicit ConcurrentUnionFind(std::uint32_t size);

  std::uint32_t size() const { return size_; }
  // Representative of x's set (path halving, safe under concurrent unite()).
  std::uint32_t find(std::uint32_t x);
  void unite(std::uint32_t a, std::uint32_t b);

 private:
  std::uint32_t size_;
  std::unique_ptr<std::atomic<std::uint32_t>[]> parent_;
};

}  // namespace lccp
