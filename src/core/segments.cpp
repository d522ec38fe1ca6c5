#include "lccp/core/segments.hpp"

#include <algorithm>
#include <numeric>
#include <optional>
#include <tuple>

#include <tbb/parallel_for.h>

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

// Segments as dense nodes with sizes (in supervoxels) and neighbour lists.
struct SegmentGraph {
  std::vector<std::uint32_t> ids;  // segment id of each node, ascending
  std::vector<std::uint32_t> size;
  std::vector<std::vector<std::uint32_t>> neighbors;
  std::vector<std::uint32_t> merged_into;  // node -> node it merged into (itself if alive)

  std::uint32_t node_of(std::uint32_t id) const {
    return static_cast<std::uint32_t>(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
  }
  std::uint32_t alive(std::uint32_t node) {
    while (merged_into[node] != node) node = merged_into[node] = merged_into[merged_into[node]];
    return node;
  }
};

SegmentGraph build_segment_graph(const std::vector<std::uint32_t>& segment_of, const std::vector<Edge>& edges) {
  SegmentGraph g;
  g.ids = segment_of;
  std::sort(g.ids.begin(), g.ids.end());
  g.ids.erase(std::unique(g.ids.begin(), g.ids.end()), g.ids.end());
  g.size.assign(g.ids.size(), 0);
  for (std::uint32_t id : segment_of) ++g.size[g.node_of(id)];
  g.neighbors.resize(g.ids.size());
  for (const Edge& e : edges) {
    const std::uint32_t a = g.node_of(segment_of[e.a]), b = g.node_of(segment_of[e.b]);
    if (a == b) continue;
    g.neighbors[a].push_back(b);
    g.neighbors[b].push_back(a);
  }
  g.merged_into.resize(g.ids.size());
  std::iota(g.merged_into.begin(), g.merged_into.end(), 0u);
  return g;
}

// The largest live neighbour of a live node (ties: smaller segment id); none if isolated.
std::optional<std::uint32_t> largest_neighbor(SegmentGraph& g, std::uint32_t node) {
  std::optional<std::uint32_t> best;
  for (std::uint32_t& n : g.neighbors[node]) {
    n = g.alive(n);
    if (n == node) continue;
    if (!best || std::tie(g.size[*best], n) < std::tie(g.size[n], *best)) best = n;
  }
  return best;
}

// One sweep over the small segments, smallest first; true if anything merged.
bool merge_sweep(SegmentGraph& g, std::uint32_t n_filter) {
  std::vector<std::uint32_t> small;
  for (std::uint32_t node = 0; node < g.ids.size(); ++node) {
    if (g.alive(node) == node && g.size[node] <= n_filter) small.push_back(node);
  }
  std::stable_sort(small.begin(), small.end(), [&](std::uint32_t a, std::uint32_t b) { return g.size[a] < g.size[b]; });
  bool merged = false;
  for (std::uint32_t node : small) {
    if (g.alive(node) != node || g.size[node] > n_filter) continue;
    const auto target = largest_neighbor(g, node);
    if (!target) continue;
    g.merged_into[node] = *target;
    g.size[*target] += g.size[node];
    auto& into = g.neighbors[*target];
    into.insert(into.end(), g.neighbors[node].begin(), g.neighbors[node].end());
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
  for (std::uint32_t& id : segment_of_supervoxel) id = g.ids[g.alive(g.node_of(id))];
}

std::uint32_t relabel_by_size(std::vector<std::uint32_t>& segment_of_supervoxel) {
  const std::size_t n = segment_of_supervoxel.size();
  // Per segment id: (size, smallest member), gathered over dense nodes.
  std::vector<std::uint32_t> ids = segment_of_supervoxel;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  const auto node_of = [&](std::uint32_t id) {
    return static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
  };
  std::vector<std::uint32_t> size(ids.size(), 0), first_member(ids.size(), static_cast<std::uint32_t>(n));
  for (std::uint32_t sv = 0; sv < n; ++sv) {
    const std::size_t node = node_of(segment_of_supervoxel[sv]);
    ++size[node];
    first_member[node] = std::min(first_member[node], sv);
  }
  std::vector<std::uint32_t> order(ids.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return std::tie(size[b], first_member[a]) < std::tie(size[a], first_member[b]);
  });
  std::vector<std::uint32_t> dense(ids.size());
  for (std::uint32_t rank = 0; rank < order.size(); ++rank) dense[order[rank]] = rank + 1;
  for (std::uint32_t& id : segment_of_supervoxel) id = dense[node_of(id)];
  return static_cast<std::uint32_t>(ids.size());
}

}  // namespace lccp
