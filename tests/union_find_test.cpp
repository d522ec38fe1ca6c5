// ConcurrentUnionFind: the partition and its representatives (the smallest member) must
// not depend on the order or the interleaving of unite() calls.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <numeric>
#include <queue>
#include <random>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include "lccp/core/union_find.hpp"

namespace lccp {
namespace {

using EdgeList = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// Component minimum of every element by a serial BFS over the (undirected) edges.
std::vector<std::uint32_t> bfs_component_min(std::uint32_t n, const EdgeList& edges) {
  std::vector<std::vector<std::uint32_t>> adj(n);
  for (auto [a, b] : edges) {
    adj[a].push_back(b);
    adj[b].push_back(a);
  }
  std::vector<std::uint32_t> comp(n, UINT32_MAX);
  for (std::uint32_t s = 0; s < n; ++s) {  // s ascending: s is its component's minimum
    if (comp[s] != UINT32_MAX) continue;
    std::queue<std::uint32_t> q;
    q.push(s);
    comp[s] = s;
    while (!q.empty()) {
      const std::uint32_t x = q.front();
      q.pop();
      for (std::uint32_t y : adj[x]) {
        if (comp[y] == UINT32_MAX) {
          comp[y] = s;
          q.push(y);
        }
      }
    }
  }
  return comp;
}

// K components of random membership: each element gets a random component, each
// component is connected by a random spanning tree (every member links to a random
// earlier member) plus a few random extra edges inside it, plus some long chains.
EdgeList random_components(std::uint32_t n, std::uint32_t k, std::mt19937& rng) {
  std::uniform_int_distribution<std::uint32_t> comp_of(0, k - 1);
  std::vector<std::vector<std::uint32_t>> members(k);
  for (std::uint32_t x = 0; x < n; ++x) members[comp_of(rng)].push_back(x);
  EdgeList edges;
  for (auto& m : members) {
    std::shuffle(m.begin(), m.end(), rng);
    for (std::size_t i = 1; i < m.size(); ++i) {
      // Every tenth component is a chain (long paths stress path halving), others trees.
      const std::size_t j = (&m - members.data()) % 10 == 0 ? i - 1 : std::uniform_int_distribution<std::size_t>(0, i - 1)(rng);
      edges.emplace_back(m[i], m[j]);
    }
    for (std::size_t e = 0; e < m.size() / 4; ++e) {
      std::uniform_int_distribution<std::size_t> pick(0, m.size() - 1);
      edges.emplace_back(m[pick(rng)], m[pick(rng)]);  // may be a self loop: harmless
    }
  }
  std::shuffle(edges.begin(), edges.end(), rng);
  return edges;
}

void expect_partition(ConcurrentUnionFind& uf, const std::vector<std::uint32_t>& expected) {
  std::size_t wrong = 0, first_wrong = 0;
  for (std::uint32_t x = 0; x < expected.size(); ++x) {
    if (uf.find(x) != expected[x]) {
      if (wrong++ == 0) first_wrong = x;
    }
  }
  EXPECT_EQ(wrong, 0u) << "first wrong element " << first_wrong << ": find " << uf.find(std::uint32_t(first_wrong))
                       << ", expected " << expected[first_wrong];
}

TEST(UnionFind, SingletonsAtStart) {
  ConcurrentUnionFind uf(10);
  EXPECT_EQ(uf.size(), 10u);
  for (std::uint32_t x = 0; x < 10; ++x) EXPECT_EQ(uf.find(x), x);
}

TEST(UnionFind, SequentialUnionsRootIsSmallestMember) {
  ConcurrentUnionFind uf(10);
  // Sets built so that the smallest member is never the first argument of the first union.
  uf.unite(7, 9);  // {7, 9}
  EXPECT_EQ(uf.find(9), 7u);
  uf.unite(9, 4);  // {4, 7, 9}
  EXPECT_EQ(uf.find(9), 4u);
  EXPECT_EQ(uf.find(7), 4u);
  uf.unite(8, 6);  // {6, 8}
  uf.unite(5, 3);  // {3, 5}
  uf.unite(8, 5);  // {3, 5, 6, 8}
  EXPECT_EQ(uf.find(6), 3u);
  EXPECT_EQ(uf.find(8), 3u);
  uf.unite(2, 2);  // self union: no change
  EXPECT_EQ(uf.find(2), 2u);
  uf.unite(9, 7);  // already together: no change
  const std::vector<std::uint32_t> expected = {0, 1, 2, 3, 4, 3, 3, 4, 3, 4};
  expect_partition(uf, expected);
  uf.unite(6, 9);  // {3, 4, 5, 6, 7, 8, 9}
  uf.unite(1, 0);  // {0, 1}
  expect_partition(uf, {0, 0, 2, 3, 3, 3, 3, 3, 3, 3});
  uf.unite(2, 8);
  uf.unite(9, 1);
  expect_partition(uf, std::vector<std::uint32_t>(10, 0));
}

TEST(UnionFind, SequentialRandomMatchesBfs) {
  std::mt19937 rng(1);
  const std::uint32_t n = 5000;
  const EdgeList edges = random_components(n, 300, rng);
  ConcurrentUnionFind uf(n);
  for (auto [a, b] : edges) uf.unite(a, b);
  expect_partition(uf, bfs_component_min(n, edges));
}

TEST(UnionFind, ConcurrentUnionsWithTbbMatchBfs) {
  const std::uint32_t n = 100000;
  for (int rep = 0; rep < 20; ++rep) {
    SCOPED_TRACE(rep);
    std::mt19937 rng(1000 + rep);
    // Few large components in some repetitions, many small ones in others.
    const std::uint32_t k = rep % 2 == 0 ? 10 + rep : 5000 + 1000 * rep;
    const EdgeList edges = random_components(n, k, rng);
    const std::vector<std::uint32_t> expected = bfs_component_min(n, edges);
    ConcurrentUnionFind uf(n);
    tbb::parallel_for(std::size_t{0}, edges.size(), [&](std::size_t e) { uf.unite(edges[e].first, edges[e].second); });
    // Representatives read concurrently too.
    std::vector<std::uint32_t> found(n);
    tbb::parallel_for(std::uint32_t{0}, n, [&](std::uint32_t x) { found[x] = uf.find(x); });
    ASSERT_EQ(found, expected);
  }
}

TEST(UnionFind, ChainsUnitedFromBothEnds) {
  // K chains of consecutive elements, united in a shuffled order in parallel; the
  // representative of every chain element is the chain's first element.
  const std::uint32_t n = 100000, k = 37;
  EdgeList edges;
  std::vector<std::uint32_t> expected(n);
  const std::uint32_t len = n / k;
  for (std::uint32_t x = 0; x < n; ++x) {
    const std::uint32_t chain = std::min(x / len, k - 1);
    expected[x] = chain * len;
    if (x > chain * len) edges.emplace_back(x, x - 1);
  }
  for (int rep = 0; rep < 20; ++rep) {
    std::mt19937 rng(rep);
    std::shuffle(edges.begin(), edges.end(), rng);
    if (rep % 2) for (auto& e : edges) std::swap(e.first, e.second);
    ConcurrentUnionFind uf(n);
    tbb::parallel_for(std::size_t{0}, edges.size(), [&](std::size_t e) { uf.unite(edges[e].first, edges[e].second); });
    std::vector<std::uint32_t> found(n);
    for (std::uint32_t x = 0; x < n; ++x) found[x] = uf.find(x);
    ASSERT_EQ(found, expected) << "rep " << rep;
  }
}

TEST(UnionFind, FourStdThreadsHammeringOverlappingUnions) {
  // Every thread unites ALL edges (each in its own order and argument orientation),
  // so every union races with the same union in the other threads; meanwhile they also
  // call find(), which must always return an element <= x (links go to smaller roots).
  const std::uint32_t n = 100000;
  for (int rep = 0; rep < 5; ++rep) {
    std::mt19937 rng(4242 + rep);
    const EdgeList edges = random_components(n, 200 + 3000 * rep, rng);
    const std::vector<std::uint32_t> expected = bfs_component_min(n, edges);
    ConcurrentUnionFind uf(n);
    std::atomic<std::uint64_t> bad_find{0};
    std::atomic<int> ready{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t) {
      threads.emplace_back([&, t] {
        EdgeList mine = edges;
        std::mt19937 r(static_cast<std::uint32_t>(t * 7919 + rep));
        std::shuffle(mine.begin(), mine.end(), r);
        if (t % 2) for (auto& e : mine) std::swap(e.first, e.second);
        ready.fetch_add(1);
        while (ready.load() < 4) std::this_thread::yield();  // start together
        for (auto [a, b] : mine) {
          uf.unite(a, b);
          const std::uint32_t ra = uf.find(a);
          if (ra > a || ra > b || ra < expected[a]) bad_find.fetch_add(1);
        }
      });
    }
    for (auto& th : threads) th.join();
    EXPECT_EQ(bad_find.load(), 0u) << "rep " << rep;
    expect_partition(uf, expected);
  }
}

}  // namespace
}  // namespace lccp
