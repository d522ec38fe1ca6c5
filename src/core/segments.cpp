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
  Grouped<std::uint32_t> neighbors;        // per node: its neighbour nodes (updated to live ones)
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
Grouped<std::uint32_t> neighbor_rows(const std::vector<std::uint32_t>& node_of, const std::vector<Edge>& edges,
                                     std::size_t count) {
  return group_by_key<std::uint32_t>(count, [&](auto emit) {
    for (const Edge& e : edges) {
      const std::uint32_t a = node_of[e.a], b = node_of[e.b];
      if (a != b) emit(a, b), emit(b, a);
    }
  });
}

SegmentGraph build_segment_graph(const std::vector<std::uint32_t>& segment_of, const std::vector<Edge>& edges) {
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
  g.neighbors = neighbor_rows(g.node_of_supervoxel, edges, count);
  g.merged_into.resize(count);
  std::iota(g.merged_into.begin(), g.merged_into.end(), 0u);
  g.next_row.assign(count, SegmentGraph::kEnd);
  g.last_row = g.merged_into;
  return g;
}

// The largest live neighbour of a live node (ties: smaller segment id); none if isolated.
std::optional<std::uint32_t> largest_neighbor(SegmentGraph& g, std::uint32_t node) {
  std::optional<std::uint32_t> best;
  for (std::uint32_t row = node; row != SegmentGraph::kEnd; row = g.next_row[row]) {
    for (std::uint32_t k = g.neighbors.offsets[row]; k < g.neighbors.offsets[row + 1]; ++k) {
      const std::uint32_t n = g.neighbors.items[k] = g.alive(g.neighbors.items[k]);
      if (n == node || g.nodes.ids[n] == kNoSegment) continue;
      if (!best || std::tie(g.size[*best], n) < std::tie(g.size[n], *best)) best = n;
    }
  }
  return best;
}

// One sweep over the small segments, smallest first; true if anything merged.
bool merge_sweep(SegmentGraph& g, std::uint32_t n_filter) {
  std::vector<std::uint32_t> small;
  for (std::uint32_t node = 0; node < g.size.size(); ++node) {
    if (g.alive(node) == node && g.size[node] <= n_filter && g.nodes.ids[node] != kNoSegment) small.push_back(node);
  }
  std::stable_sort(small.begin(), small.end(), [&](std::uint32_t a, std::uint32_t b) { return g.size[a] < g.size[b]; });
  bool merged = false;
  for (std::uint32_t node : small) {
    if (g.alive(node) != node || g.size[node] > n_filter) continue;
    const auto target = largest_neighbor(g, node);
    if (!target) continue;
    g.merge(node, *target);
    merged = true;
  }
  return merged;
}

}  // namespace

void merge_small_segments(std::vector<std::uint32_t>& segment_of_supervoxel, const std::vector<Edge>& edges,
                          std::uint32_t n_filter) {
  if (n_filter == 0 || segment_of_supervoxel.empty()) return;
  SegmentGraph g = build_segment_graph(segment_of_supervoxel, edges);
  while (merge_sweep(g, n_filter)) {
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
