#include "lccp/core/segments.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <numeric>
#include <optional>
#include <tuple>

#include <tbb/parallel_for.h>

#include "cell_keys.hpp"
#include "lccp/core/grouped.hpp"
#include "lccp/core/union_find.hpp"

namespace lccp {

std::vector<std::uint32_t> convex_components(std::size_t supervoxel_count, const std::vector<Edge>& edges,
                                             const std::vector<std::uint8_t>& convex) {
  ConcurrentUnionFind sets(static_cast<std::uint32_t>(supervoxel_count));
  tbb::parallel_for(std::size_t{0}, edges.size(), [&](std::size_t e) {
    if (convex[e]) sets.unite(edges[e].a, edges[e].b);
  });
  std::vector<std::uint32_t> segment(supervoxel_count);
  tbb::parallel_for(std::uint32_t{0}, static_cast<std::uint32_t>(supervoxel_count),
                    [&](std::uint32_t i) { segment[i] = sets.find(i); });
  return segment;
}

namespace {

// The segments as dense nodes 0..S-1 in ascending id: each node's id and its
// member supervoxels (ascending). One stable radix sort of (id, supervoxel):
// linear in the supervoxels, where a search per look-up is not (a room-scale
// frame has some 50 000 supervoxels and 130 000 edges).
struct SegmentNodes {
  std::vector<std::uint64_t> ids;
  CompressedRows members;
};

SegmentNodes segment_nodes(const std::vector<std::uint32_t>& segment_of) {
  const std::uint32_t largest_id = *std::max_element(segment_of.begin(), segment_of.end());
  const detail::PackedKeys packing{static_cast<int>(std::bit_width(segment_of.size() - 1)),
                                   static_cast<int>(std::bit_width(largest_id))};
  std::vector<std::uint64_t> values(segment_of.size());
  for (std::uint32_t sv = 0; sv < segment_of.size(); ++sv) values[sv] = packing.pack(segment_of[sv], sv);
  detail::radix_sort(values, packing);
  SegmentNodes nodes;
  detail::group_runs(values, packing, nodes.ids, nodes.members);
  return nodes;
}

// A neighbour across one edge, that edge's convexity (eq. (1)'s measure), and
// whether the row's node rests on the neighbour across it (EdgeRanks::resting).
struct Neighbor {
  std::uint32_t node = 0;
  float convexity = 0.0f;
  bool rests = false;
};

// Segments as dense nodes with sizes (in supervoxels) and neighbour rows: one
// row per node as the edges give it (with repeats), grouped in one array
// (lccp/core/grouped.hpp), so that no node owns an allocation. A node merged
// into another hands it its rows: a live node's neighbours are the rows on its
// chain (itself, then the nodes merged into it, in merge order), which is what
// appending the lists would give.
struct SegmentGraph {
  static constexpr std::uint32_t kEnd = std::numeric_limits<std::uint32_t>::max();

  SegmentNodes nodes;
  std::vector<std::uint32_t> node_of_supervoxel;
  std::vector<std::uint32_t> size;
  Grouped<Neighbor> neighbors;             // per node: its neighbour nodes (updated to live ones)
  std::vector<std::uint32_t> merged_into;  // node -> node it merged into (itself if alive)
  std::vector<std::uint32_t> next_row;     // per node: the next node on its chain of rows (kEnd: none)
  std::vector<std::uint32_t> last_row;     // per live node: the last node on its chain

  std::uint32_t alive(std::uint32_t node) {
    while (merged_into[node] != node) node = merged_into[node] = merged_into[merged_into[node]];
    return node;
  }
  void merge(std::uint32_t node, std::uint32_t into) {
    merged_into[node] = into;
    size[into] += size[node];
    next_row[last_row[into]] = node, last_row[into] = last_row[node];
  }
};

// The nodes' neighbour rows in edge order.
Grouped<Neighbor> neighbor_rows(const std::vector<std::uint32_t>& node_of, const std::vector<Edge>& edges,
                                const EdgeRanks& ranks, std::size_t count) {
  return group_by_key<Neighbor>(count, [&](auto emit) {
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const std::uint32_t a = node_of[edges[e].a], b = node_of[edges[e].b];
      const float c = ranks.convexity.empty() ? 0.0f : ranks.convexity[e];
      const std::uint8_t r = ranks.resting.empty() ? 0 : ranks.resting[e];
      if (a != b) emit(a, Neighbor{b, c, r == kARestsOnB}), emit(b, Neighbor{a, c, r == kBRestsOnA});
    }
  });
}

SegmentGraph build_segment_graph(const std::vector<std::uint32_t>& segment_of, const std::vector<Edge>& edges,
                                 const EdgeRanks& ranks) {
  SegmentGraph g;
  g.nodes = segment_nodes(segment_of);
  const std::size_t count = g.nodes.ids.size();
  g.size.resize(count);
  g.node_of_supervoxel.resize(segment_of.size());
  for (std::uint32_t node = 0; node < count; ++node) {
    g.size[node] = g.nodes.members.count(node);
    for (const std::uint32_t* sv = g.nodes.members.begin(node); sv != g.nodes.members.end(node); ++sv) {
      g.node_of_supervoxel[*sv] = node;
    }
  }
  g.neighbors = neighbor_rows(g.node_of_supervoxel, edges, ranks, count);
  g.merged_into.resize(count);
  std::iota(g.merged_into.begin(), g.merged_into.end(), 0u);
  g.next_row.assign(count, SegmentGraph::kEnd);
  g.last_row = g.merged_into;
  return g;
}

// Which neighbour a small segment joins (A.4): its largest, or by_convexity
// the one across its most convex edge (each ranked by its size next, then by
// the smaller node).
enum class Rule { largest, by_convexity };

// The live neighbour of a live node that `rule` ranks first, after those
// across an edge on which the node does not rest (EdgeRanks::resting); none
// if isolated, and by_convexity none if that neighbour is small (the node
// waits for it).
std::optional<std::uint32_t> merge_target(SegmentGraph& g, std::uint32_t node, std::uint32_t n_filter, Rule rule) {
  std::optional<std::uint32_t> best;
  float best_convexity = 0.0f;
  bool best_free = false;
  for (std::uint32_t row = node; row != SegmentGraph::kEnd; row = g.next_row[row]) {
    for (std::uint32_t k = g.neighbors.offsets[row]; k < g.neighbors.offsets[row + 1]; ++k) {
      Neighbor& m = g.neighbors.items[k];
      const std::uint32_t n = m.node = g.alive(m.node);
      if (n == node || g.nodes.ids[n] == kNoSegment) continue;
      const float c = rule == Rule::by_convexity ? m.convexity : 0.0f;
      const bool free = !m.rests;
      if (!best || std::tuple(free, c, g.size[n], *best) > std::tuple(best_free, best_convexity, g.size[*best], n)) {
        best = n, best_convexity = c, best_free = free;
      }
    }
  }
  if (rule == Rule::by_convexity && best && g.size[*best] <= n_filter) return std::nullopt;
  return best;
}

// One sweep over the small segments, smallest first; true if anything merged.
bool merge_sweep(SegmentGraph& g, std::uint32_t n_filter, Rule rule) {
  std::vector<std::uint32_t> small;
  for (std::uint32_t node = 0; node < g.size.size(); ++node) {
    if (g.alive(node) == node && g.size[node] <= n_filter && g.nodes.ids[node] != kNoSegment) small.push_back(node);
  }
  std::stable_sort(small.begin(), small.end(), [&](std::uint32_t a, std::uint32_t b) { return g.size[a] < g.size[b]; });
  bool merged = false;
  for (std::uint32_t node : small) {
    if (g.alive(node) != node || g.size[node] > n_filter) continue;
    const auto target = merge_target(g, node, n_filter, rule);
    if (!target) continue;
    g.merge(node, *target);
    merged = true;
  }
  return merged;
}

}  // namespace

void merge_small_segments(std::vector<std::uint32_t>& segment_of_supervoxel, const std::vector<Edge>& edges,
                          std::uint32_t n_filter, const EdgeRanks& ranks) {
  if (n_filter == 0 || segment_of_supervoxel.empty()) return;
  SegmentGraph g = build_segment_graph(segment_of_supervoxel, edges, ranks);
  while (!ranks.convexity.empty() && merge_sweep(g, n_filter, Rule::by_convexity)) {
  }
  while (merge_sweep(g, n_filter, Rule::largest)) {
  }
  for (std::uint32_t sv = 0; sv < segment_of_supervoxel.size(); ++sv) {
    segment_of_supervoxel[sv] = static_cast<std::uint32_t>(g.nodes.ids[g.alive(g.node_of_supervoxel[sv])]);
  }
}

std::uint32_t relabel_by_size(std::vector<std::uint32_t>& segment_of_supervoxel) {
  if (segment_of_supervoxel.empty()) return 0;
  const SegmentNodes nodes = segment_nodes(segment_of_supervoxel);
  const CompressedRows& members = nodes.members;
  // Largest first, ties by smallest member (the first of its ascending members).
  std::vector<std::uint32_t> order;
  for (std::uint32_t node = 0; node < members.rows(); ++node) {
    if (nodes.ids[node] != kNoSegment) {
      order.push_back(node);
      continue;
    }
    for (const std::uint32_t* sv = members.begin(node); sv != members.end(node); ++sv) segment_of_supervoxel[*sv] = 0;
  }
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return std::tuple(members.count(b), *members.begin(a)) < std::tuple(members.count(a), *members.begin(b));
  });
  for (std::uint32_t rank = 0; rank < order.size(); ++rank) {
    for (const std::uint32_t* sv = members.begin(order[rank]); sv != members.end(order[rank]); ++sv) {
      segment_of_supervoxel[*sv] = rank + 1;
    }
  }
  return static_cast<std::uint32_t>(order.size());
}

}  // namespace lccp
