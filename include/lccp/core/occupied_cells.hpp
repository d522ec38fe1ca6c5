#pragma once
// Which cells of a grid each segment of a labelled cloud occupies: the overlap
// measure of the stable ids (lccp/objects/tracking.hpp). Segments at two
// levels, objects and their parts, in one index space: objects
// 0..object_count-1, then the parts; an object occupies its parts' cells and
// those of its points without a part.
//
// Two grids, the second shifted by half a cell on every axis, both counted in a
// segment's cells. A flat face square to an axis (a box front seen head-on)
// moving 5 mm along its normal can cross a cell boundary of one grid and leave
// every cell it occupied there; it cannot cross one of each grid in the same
// frame (their boundaries are half a cell apart), so the worst case keeps
// IoU >= 1/3 where one grid would drop to 0. (A 10 cm box moving 2.9 mm along
// each axis, its faces on cell boundaries: with one grid its IoU fell to 0.05
// as all six faces crossed at once, and it lost its id.)
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "lccp/cloud.hpp"

namespace lccp {

// One frame's segments at both levels, as dense per-point labels (0 = none).
struct FrameSegments {
  std::span<const Eigen::Vector3f> points;  // metres
  const Labels* objects = nullptr;  // per point: object 1..object_count
  std::uint32_t object_count = 0;
  const Labels* parts = nullptr;  // per point: part 1..part_count; null: no part level
  std::uint32_t part_count = 0;
};

// A segment in a cell. The cell's key: the grid bit (bit 63), then 21 bits per
// axis (x-major) of the cell's index + 2^20.
struct OccupiedCell {
  std::uint64_t cell = 0;
  std::uint32_t segment = 0;
};

// Ascending (cell, segment): the order of OccupiedCells::grids.
inline bool operator<(const OccupiedCell& a, const OccupiedCell& b) {
  return a.cell != b.cell ? a.cell < b.cell : a.segment < b.segment;
}

inline constexpr std::uint32_t kNoObject = std::numeric_limits<std::uint32_t>::max();

struct OccupiedCells {
  std::array<std::vector<OccupiedCell>, 2> grids;  // per grid: ascending (cell, segment), no repeats
  std::vector<std::uint32_t> part_object;          // per part: its object, 0-based (kNoObject: no point)
};

// The cells of side cell_size (metres) the segments of `frame` occupy on both
// grids. Points that are not finite or lie 2^20 cells or more from the origin
// on an axis are left out. The same cells for any thread count. Throws
// lccp::Error for a label above its count.
OccupiedCells occupied_cells(const FrameSegments& frame, float cell_size);

// Sorts keys below 2^bits ascending: the core's radix sort (linear, parallel
// over fixed blocks), for the tracker's keys of segment pairs.
void sort_keys(std::vector<std::uint64_t>& keys, int bits);

// How many cells each of `segment_count` segments occupies, both grids counted.
std::vector<std::uint32_t> cell_counts(const OccupiedCells& cells, std::uint32_t segment_count);

}  // namespace lccp
