// Convex connected components (A.3), the noise filter (A.4) and the final relabelling.
#include <algorithm>
#include <cstdint>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "lccp/core/segments.hpp"

namespace lccp {
namespace {

// Partition as a canonical form: each element mapped to the smallest element sharing its
// label. Two labelings describe the same partition iff their canonical forms are equal.
std::vector<std::uint32_t> canonical(const std::vector<std::uint32_t>& labels) {
  std::map<std::uint32_t, std::uint32_t> first;
  std::vector<std::uint32_t> out(labels.size());
  for (std::uint32_t i = 0; i < labels.size(); ++i) {
    auto [it, inserted] = first.emplace(labels[i], i);
    out[i] = it->second;
  }
  return out;
}

std::vector<Edge> chain_edges(std::uint32_t first, std::uint32_t last) {
  std::vector<Edge> e;
  for (std::uint32_t i = first; i < last; ++i) e.push_back({i, i + 1});
  return e;
}

void sort_edges(std::vector<Edge>& edges) {
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
}

// --- convex_components ---------------------------------------------------------------------

TEST(ConvexComponents, HandDrawnGraph) {
  // 8 supervoxels. Convex (c) and non-convex (x) edges:
  //
  //   0 -c- 1 -x- 2 -c- 3
  //   |x    |c        |c
  //   6     5 -x- 4 --+        4 -c- 7,   6 -x- 7
  //
  // Components over convex edges: {0, 1, 5}, {2, 3, 4, 7}, {6}; ids = smallest member.
  const std::vector<Edge> edges = {{0, 1}, {0, 6}, {1, 2}, {1, 5}, {2, 3}, {3, 4}, {4, 5}, {4, 7}, {6, 7}};
  const std::vector<std::uint8_t> convex = {1, 0, 0, 1, 1, 1, 0, 1, 0};
  const auto seg = convex_components(8, edges, convex);
  EXPECT_EQ(seg, (std::vector<std::uint32_t>{0, 0, 2, 2, 2, 0, 6, 2}));
}

TEST(ConvexComponents, NoEdgesAndAllConvex) {
  EXPECT_EQ(convex_components(4, {}, {}), (std::vector<std::uint32_t>{0, 1, 2, 3}));
  const std::vector<Edge> edges = {{2, 3}, {1, 3}, {0, 2}};
  EXPECT_EQ(convex_components(5, edges, {1, 1, 1}), (std::vector<std::uint32_t>{0, 0, 0, 0, 4}));
  EXPECT_EQ(convex_components(5, edges, {0, 0, 0}), (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
  EXPECT_TRUE(convex_components(0, {}, {}).empty());
}

TEST(ConvexComponents, MinimumReachedOnlyThroughALongPath) {
  // Component {3, 9, 12, 20, 40} joined as a path 40-20-12-9-3 plus a concave shortcut
  // 3-40; the id of all five is 3. Everything else stays alone.
  std::vector<Edge> edges = {{3, 9}, {9, 12}, {12, 20}, {20, 40}, {3, 40}, {0, 41}};
  std::vector<std::uint8_t> convex = {1, 1, 1, 1, 0, 0};
  const auto seg = convex_components(42, edges, convex);
  for (std::uint32_t i = 0; i < 42; ++i) {
    const bool in = i == 3 || i == 9 || i == 12 || i == 20 || i == 40;
    EXPECT_EQ(seg[i], in ? 3u : i) << "supervoxel " << i;
  }
}

TEST(ConvexComponents, LargeRandomGraphMatchesSerialSearch) {
  std::mt19937 rng(5);
  const std::uint32_t n = 50000;
  std::vector<Edge> edges;
  std::uniform_int_distribution<std::uint32_t> pick(0, n - 1);
  for (int k = 0; k < 60000; ++k) {
    std::uint32_t a = pick(rng), b = pick(rng);
    if (a == b) continue;
    edges.push_back({std::min(a, b), std::max(a, b)});
  }
  sort_edges(edges);
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<std::uint8_t> convex(edges.size());
  for (auto& c : convex) c = std::bernoulli_distribution(0.6)(rng);
  // Serial reference: repeated relaxation to the minimum label over convex edges.
  std::vector<std::uint32_t> ref(n);
  std::iota(ref.begin(), ref.end(), 0u);
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      if (!convex[e]) continue;
      const std::uint32_t m = std::min(ref[edges[e].a], ref[edges[e].b]);
      if (ref[edges[e].a] != m || ref[edges[e].b] != m) {
        ref[edges[e].a] = ref[edges[e].b] = m;
        changed = true;
      }
    }
  }
  EXPECT_EQ(convex_components(n, edges, convex), ref);
}

// --- merge_small_segments (A.4) ----------------------------------------------------------

// Segments of 5 {0..4}, 3 {5, 6, 7} and 1 {8} supervoxels; 8 touches 4 and 5.
struct SmallBetweenTwo {
  std::vector<std::uint32_t> seg = {0, 0, 0, 0, 0, 5, 5, 5, 8};
  std::vector<Edge> edges;
  SmallBetweenTwo() {
    edges = chain_edges(0, 4);
    for (auto e : chain_edges(5, 7)) edges.push_back(e);
    edges.push_back({4, 8});
    edges.push_back({5, 8});
    sort_edges(edges);
  }
};

TEST(MergeSmallSegments, SingleMergesIntoLargestNeighbour) {
  // n_filter 2: only {8} (size 1) is small; its neighbours have 5 and 3 supervoxels -> it
  // joins the 5. The 3-segment is not small (3 > 2) and stays.
  SmallBetweenTwo g;
  merge_small_segments(g.seg, g.edges, 2);
  EXPECT_EQ(canonical(g.seg), (std::vector<std::uint32_t>{0, 0, 0, 0, 0, 5, 5, 5, 0}));
  EXPECT_EQ(g.seg[8], g.seg[0]);
  EXPECT_NE(g.seg[5], g.seg[0]);
}

TEST(MergeSmallSegments, SmallerOrEqualToFilterSizeMerges) {
  // n_filter 3: "|S_i| smaller or equal to the filter size" -> {8} merges into the 5
  // (now 6), then the 3-segment, whose only neighbour is that segment, merges too.
  SmallBetweenTwo g;
  merge_small_segments(g.seg, g.edges, 3);
  EXPECT_EQ(canonical(g.seg), std::vector<std::uint32_t>(9, 0));
}

TEST(MergeSmallSegments, FilterZeroChangesNothing) {
  SmallBetweenTwo g;
  const auto before = g.seg;
  merge_small_segments(g.seg, g.edges, 0);
  EXPECT_EQ(g.seg, before);
}

TEST(MergeSmallSegments, IsolatedSmallSegmentStays) {
  // {9} and {10, 11} have no edge to another segment (10-11 is internal): they stay even
  // though they are small. {8} still merges into the 5.
  SmallBetweenTwo g;
  g.seg.push_back(9);
  g.seg.push_back(10);
  g.seg.push_back(10);
  g.edges.push_back({10, 11});
  merge_small_segments(g.seg, g.edges, 2);
  EXPECT_EQ(canonical(g.seg), (std::vector<std::uint32_t>{0, 0, 0, 0, 0, 5, 5, 5, 0, 9, 10, 10}));
}

TEST(MergeSmallSegments, TiesGoToTheSmallerId) {
  // {4} touches two segments of 2 supervoxels each, ids 0 {0, 1} and 2 {2, 3}. Filter 1:
  // only {4} is small; tie on size -> the smaller id, 0.
  std::vector<std::uint32_t> seg = {0, 0, 2, 2, 4};
  const std::vector<Edge> edges = {{0, 1}, {1, 4}, {2, 3}, {3, 4}};
  merge_small_segments(seg, edges, 1);
  EXPECT_EQ(canonical(seg), (std::vector<std::uint32_t>{0, 0, 2, 2, 0}));
  // Same with the ids swapped around: {0, 1} carries id 7, {2, 3} id 2 -> joins id 2.
  seg = {7, 7, 2, 2, 4};
  merge_small_segments(seg, edges, 1);
  EXPECT_EQ(canonical(seg), (std::vector<std::uint32_t>{0, 0, 2, 2, 2}));
}

TEST(MergeSmallSegments, MergedSegmentStillSmallMergesAgain) {
  // X = {0} (1 sv) touches only Y = {1, 2} (2 sv); Y touches Z = {3..12} (10 sv).
  // n_filter 3: X is visited first (smallest) and joins its only neighbour Y -> Y has 3
  // supervoxels, still <= 3 -> it merges again, into Z: one segment.
  std::vector<std::uint32_t> seg = {0, 1, 1};
  for (int i = 0; i < 10; ++i) seg.push_back(3);
  std::vector<Edge> edges = {{0, 1}, {1, 2}, {2, 3}};
  for (auto e : chain_edges(3, 12)) edges.push_back(e);
  sort_edges(edges);
  auto s3 = seg;
  merge_small_segments(s3, edges, 3);
  EXPECT_EQ(canonical(s3), std::vector<std::uint32_t>(13, 0));
  // n_filter 2: X joins Y (Y's size 2 is the largest neighbour of X), X+Y = 3 > 2 stops.
  auto s2 = seg;
  merge_small_segments(s2, edges, 2);
  EXPECT_EQ(canonical(s2), (std::vector<std::uint32_t>{0, 0, 0, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3}));
}

TEST(MergeSmallSegments, NoSegmentIsNeitherMergedNorMergedInto) {
  // The support's supervoxels (kNoSegment, 6 of them) touch {8}; n_filter 2: {8} joins
  // its largest neighbour that is a segment, the 5 (not the 6 support supervoxels), and
  // the support's supervoxels stay as they are, though {8} was merged into nothing of them.
  SmallBetweenTwo g;
  for (int i = 0; i < 6; ++i) g.seg.push_back(kNoSegment);
  for (auto e : chain_edges(9, 14)) g.edges.push_back(e);
  g.edges.push_back({8, 9});
  sort_edges(g.edges);
  merge_small_segments(g.seg, g.edges, 2);
  EXPECT_EQ(g.seg[8], g.seg[0]);
  for (std::size_t sv = 9; sv < g.seg.size(); ++sv) EXPECT_EQ(g.seg[sv], kNoSegment);
  // relabel_by_size: the support's supervoxels get 0, the segments 1 (6 supervoxels) and 2.
  EXPECT_EQ(relabel_by_size(g.seg), 2u);
  EXPECT_EQ(g.seg, (std::vector<std::uint32_t>{1, 1, 1, 1, 1, 2, 2, 2, 1, 0, 0, 0, 0, 0, 0}));
}

// Per edge of `edges`: 0, but `value` for the edges in `marked`.
template <typename T>
std::vector<T> per_edge_but(const std::vector<Edge>& edges, const std::vector<Edge>& marked, T value) {
  std::vector<T> per_edge(edges.size(), T{0});
  for (std::size_t e = 0; e < edges.size(); ++e) {
    for (const Edge& m : marked) {
      if (edges[e].a == m.a && edges[e].b == m.b) per_edge[e] = value;
    }
  }
  return per_edge;
}

// Eq. (1)'s measure per edge: 0 (flat), but `value` for the edges in `marked`.
std::vector<float> convexity_but(const std::vector<Edge>& edges, const std::vector<Edge>& marked, float value) {
  return per_edge_but(edges, marked, value);
}

// Per edge: kARestsOnB or kBRestsOnA (`side`) for the edges in `marked`, 0 for the others.
std::vector<std::uint8_t> resting_but(const std::vector<Edge>& edges, const std::vector<Edge>& marked,
                                      std::uint8_t side) {
  return per_edge_but(edges, marked, side);
}

TEST(MergeSmallSegments, SmallJoinsTheNeighbourAcrossItsMostConvexEdge) {
  // {8} meets the 5 across a deep concavity (edge 4-8, eq. (1)'s measure -1) and the 3
  // across a flat edge (5-8, 0): n_filter 2, it joins the 3, though the 5 is larger.
  SmallBetweenTwo g;
  merge_small_segments(g.seg, g.edges, 2, EdgeRanks{convexity_but(g.edges, {{4, 8}}, -1.0f), {}});
  EXPECT_EQ(canonical(g.seg), (std::vector<std::uint32_t>{0, 0, 0, 0, 0, 5, 5, 5, 5}));
  // Both edges alike: the larger, as the paper's filter gives it.
  g = SmallBetweenTwo{};
  merge_small_segments(g.seg, g.edges, 2, EdgeRanks{convexity_but(g.edges, {}, 0.0f), {}});
  EXPECT_EQ(canonical(g.seg), (std::vector<std::uint32_t>{0, 0, 0, 0, 0, 5, 5, 5, 0}));
}

TEST(MergeSmallSegments, ASmallSegmentJoinsANeighbourItDoesNotRestOn) {
  // {8} stands on the 5's upward face (edge 4-8, 8 is its b side) and meets the 3 beside
  // it: it joins the 3, by either rule, though the 5 is larger and, by convexity, more
  // convexly joined.
  SmallBetweenTwo g;
  merge_small_segments(g.seg, g.edges, 2, EdgeRanks{{}, resting_but(g.edges, {{4, 8}}, kBRestsOnA)});
  EXPECT_EQ(canonical(g.seg), (std::vector<std::uint32_t>{0, 0, 0, 0, 0, 5, 5, 5, 5}));
  g = SmallBetweenTwo{};
  merge_small_segments(g.seg, g.edges, 2,
                       EdgeRanks{convexity_but(g.edges, {{5, 8}}, -1.0f), resting_but(g.edges, {{4, 8}}, kBRestsOnA)});
  EXPECT_EQ(canonical(g.seg), (std::vector<std::uint32_t>{0, 0, 0, 0, 0, 5, 5, 5, 5}));
  // The other way round (the 5's supervoxel 4 rests on 8) ranks nothing: {8} joins the 5.
  g = SmallBetweenTwo{};
  merge_small_segments(g.seg, g.edges, 2, EdgeRanks{{}, resting_but(g.edges, {{4, 8}}, kARestsOnB)});
  EXPECT_EQ(canonical(g.seg), (std::vector<std::uint32_t>{0, 0, 0, 0, 0, 5, 5, 5, 0}));
  // Resting on both, it joins the largest, as in the paper.
  g = SmallBetweenTwo{};
  merge_small_segments(g.seg, g.edges, 2, EdgeRanks{{}, resting_but(g.edges, {{4, 8}, {5, 8}}, kBRestsOnA)});
  EXPECT_EQ(canonical(g.seg), (std::vector<std::uint32_t>{0, 0, 0, 0, 0, 5, 5, 5, 0}));
}

TEST(MergeSmallSegments, AFragmentFollowsTheFragmentItContinues) {
  // A = {0..5} (6 sv) - B = {6, 7, 8} (3) - C = {9} (1) - D = {10..19} (10) in a chain;
  // C meets D across a deep concavity, every other edge is flat. n_filter 3: C, visited
  // first, is most convexly joined to B, which is small: it waits; B joins A (flat,
  // not small); then C meets A through B's edge and joins it, not D, its largest neighbour.
  const std::vector<std::uint32_t> start = {0, 0, 0, 0, 0, 0, 6, 6, 6, 9, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10};
  std::vector<Edge> edges = chain_edges(0, 19);
  sort_edges(edges);
  std::vector<std::uint32_t> seg = start;
  merge_small_segments(seg, edges, 3, EdgeRanks{convexity_but(edges, {{9, 10}}, -1.0f), {}});
  EXPECT_EQ(canonical(seg), (std::vector<std::uint32_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 10, 10, 10, 10, 10, 10, 10,
                                                        10, 10, 10}));
  // The paper's filter gives C to D, then B, which now meets D, to D too.
  seg = start;
  merge_small_segments(seg, edges, 3);
  EXPECT_EQ(canonical(seg), (std::vector<std::uint32_t>{0, 0, 0, 0, 0, 0, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6}));
}

TEST(MergeSmallSegments, LongChainOfSingletonsCollapses) {
  // 0 - 1 - 2 - ... - 9, every supervoxel its own segment, n_filter 3: merging must be
  // repeated until no small segment with a neighbour is left -> with 10 supervoxels in a
  // connected graph the result is a set of segments all > 3, here necessarily 1 or 2
  // segments (sizes >= 4 summing to 10).
  std::vector<std::uint32_t> seg(10);
  std::iota(seg.begin(), seg.end(), 0u);
  merge_small_segments(seg, chain_edges(0, 9), 3);
  std::map<std::uint32_t, int> size;
  for (auto s : seg) ++size[s];
  for (auto [id, n] : size) EXPECT_GT(n, 3) << "segment " << id;
}

// Property check on random graphs: (1) the result only coarsens the input partition,
// (2) no segment of <= n_filter supervoxels keeps a neighbouring segment ("filtering
// continues until no segments (that have neighbors) smaller than the filter size are
// present"), (3) the call is deterministic.
TEST(MergeSmallSegments, RandomGraphsInvariants) {
  for (std::uint32_t rep = 0; rep < 30; ++rep) {
    SCOPED_TRACE(rep);
    std::mt19937 rng(rep);
    const std::uint32_t n = 400;
    std::vector<Edge> edges;
    std::uniform_int_distribution<std::uint32_t> pick(0, n - 1);
    for (std::uint32_t k = 0; k < n; ++k) {
      std::uint32_t a = pick(rng), b = pick(rng);
      if (a != b) edges.push_back({std::min(a, b), std::max(a, b)});
    }
    sort_edges(edges);
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::vector<std::uint8_t> convex(edges.size());
    for (auto& c : convex) c = std::bernoulli_distribution(0.5)(rng);
    const std::vector<std::uint32_t> before = convex_components(n, edges, convex);
    const std::uint32_t n_filter = 1 + rep % 4;
    std::vector<std::uint32_t> after = before;
    merge_small_segments(after, edges, n_filter);
    ASSERT_EQ(after.size(), before.size());
    // (1) coarsening: supervoxels together before are together after.
    std::map<std::uint32_t, std::uint32_t> to;
    for (std::uint32_t i = 0; i < n; ++i) {
      auto [it, inserted] = to.emplace(before[i], after[i]);
      ASSERT_EQ(it->second, after[i]) << "segment " << before[i] << " was split";
    }
    // (2) no small segment with a neighbour.
    std::map<std::uint32_t, std::uint32_t> size;
    for (auto s : after) ++size[s];
    for (const Edge& e : edges) {
      if (after[e.a] == after[e.b]) continue;
      EXPECT_GT(size[after[e.a]], n_filter) << "segment " << after[e.a] << " is small and has a neighbour";
      EXPECT_GT(size[after[e.b]], n_filter) << "segment " << after[e.b] << " is small and has a neighbour";
    }
    // (3) deterministic.
    std::vector<std::uint32_t> again = before;
    merge_small_segments(again, edges, n_filter);
    EXPECT_EQ(again, after);
  }
}

// --- relabel_by_size ---------------------------------------------------------------------

TEST(RelabelBySize, DenseLargestFirstTiesBySmallestMember) {
  // Segment ids (not dense, not equal to members):
  //   id 9: supervoxels {0, 1}         size 2, smallest member 0
  //   id 3: supervoxels {2, 3, 4}      size 3
  //   id 2: supervoxels {5, 6}         size 2, smallest member 5
  //   id 0: supervoxel  {7}            size 1
  //   id 50: supervoxels {8, 9, 10}    size 3, smallest member 8 (ties with id 3's 2)
  // Largest first: id 3 (3, member 2) -> 1, id 50 (3, member 8) -> 2, id 9 (2, member 0)
  // -> 3, id 2 (2, member 5) -> 4, id 0 -> 5.
  std::vector<std::uint32_t> seg = {9, 9, 3, 3, 3, 2, 2, 0, 50, 50, 50};
  const std::uint32_t k = relabel_by_size(seg);
  EXPECT_EQ(k, 5u);
  EXPECT_EQ(seg, (std::vector<std::uint32_t>{3, 3, 1, 1, 1, 4, 4, 5, 2, 2, 2}));
}

TEST(RelabelBySize, SingleSegmentAndEmpty) {
  std::vector<std::uint32_t> seg(7, 42);
  EXPECT_EQ(relabel_by_size(seg), 1u);
  EXPECT_EQ(seg, std::vector<std::uint32_t>(7, 1));
  std::vector<std::uint32_t> none;
  EXPECT_EQ(relabel_by_size(none), 0u);
}

TEST(RelabelBySize, InterleavedMembers) {
  // ids with members interleaved: id 4 {1, 3, 5, 7}, id 1 {0, 2, 4, 6} (tie at 4: smallest
  // member 0 < 1 -> id 1 first), id 8 {8}.
  std::vector<std::uint32_t> seg = {1, 4, 1, 4, 1, 4, 1, 4, 8};
  EXPECT_EQ(relabel_by_size(seg), 3u);
  EXPECT_EQ(seg, (std::vector<std::uint32_t>{1, 2, 1, 2, 1, 2, 1, 2, 3}));
}

}  // namespace
}  // namespace lccp
