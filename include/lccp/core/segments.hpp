#pragma once
// Stages 7-8 (kStages): convex connected components (A.3) and the noise filter (A.4).
#include <cstdint>
#include <vector>

#include "lccp/core/adjacency.hpp"

namespace lccp {

// The id of supervoxels in no segment (the support's, SupportPlaneConfig::
// decided_by_patches): the filter neither merges them nor into them, and
// relabel_by_size gives them 0.
inline constexpr std::uint32_t kNoSegment = 0xffffffffu;

// Segment id per supervoxel: components over the edges flagged convex,
// computed with the concurrent union-find. Ids are the smallest supervoxel
// index of each component (not dense).
std::vector<std::uint32_t> convex_components(std::size_t supervoxel_count, const std::vector<Edge>& edges,
                                             const std::vector<std::uint8_t>& convex);

// What the noise filter may read per edge besides the graph (each empty, or
// one per edge): eq. (1)'s measure (edge_convexity), and which side of the
// edge rests on the other's upward face (kARestsOnB, kBRestsOnA; 0: neither).
inline constexpr std::uint8_t kARestsOnB = 1, kBRestsOnA = 2;
struct EdgeRanks {
  std::vector<float> convexity;
  std::vector<std::uint8_t> resting;
};

// The noise filter (A.4): every segment of <= n_filter supervoxels merges
// into a neighbouring segment, repeatedly, until no such segment has a
// neighbour (kNoSegment is none). First, given the convexity
// (FilterConfig::by_convexity), each joins the neighbour across its most
// convex edge if that neighbour is not small, until none does; then each that
// is left joins its largest neighbour (ties: smaller id), as in the paper.
// Given `resting`, either rule first ranks the edges on which the segment does
// not rest above those on which it does. Small segments are visited smallest
// first, then by id, so the result is deterministic.
void merge_small_segments(std::vector<std::uint32_t>& segment_of_supervoxel, const std::vector<Edge>& edges,
                          std::uint32_t n_filter, const EdgeRanks& ranks = {});

// Renumbers segments densely 1..K: largest segment (in supervoxels) first,
// ties by smallest member supervoxel; kNoSegment becomes 0. Returns K.
std::uint32_t relabel_by_size(std::vector<std::uint32_t>& segment_of_supervoxel);

}  // namespace lccp
