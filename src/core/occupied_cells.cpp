#include "lccp/core/occupied_cells.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "cell_keys.hpp"
#include "lccp/error.hpp"

// Speed (the tracker on a VGA frame: 307,200 points, 10 objects, 100 parts;
// median 1.6 ms on 2 cores, 2.8 ms on 1, of a shared 2-core EPYC VM): cells are sortable 64-bit
// keys, not hash sets. Points are scanned in parallel blocks, in loops the
// compiler vectorizes; a point makes keys only where its cells or segment
// differ from the point before's, and a cache of recent keys drops most
// repeats; the keys of each grid are radix-sorted, and two frames' sorted cells
// are merged in one pass. Only parts make keys: an object's cells are those of
// its parts (and of its points without a part).
namespace lccp {
namespace {

// Cell keys (OccupiedCell::cell): the grid bit, then 21 bits per axis (x-major):
// |coordinate| < 2^20 cells (10 km); points beyond (no depth sensor measures
// them) are not matched.
constexpr int kAxisBits = 21;
// The sort packs fewer: 12 bits per axis, cells within 2048 (20 m) of the
// frame's first point, as a depth sensor's (range < 10 m) all are; frames that
// spread farther take a slower path.
constexpr int kFrameAxisBits = 12;
constexpr std::uint32_t kNone = kNoObject;  // no segment
constexpr int kFar = std::numeric_limits<int>::min();  // a coordinate not finite or too far out

// A frame's segments in one index space (objects 0..objects-1, then the
// parts), and its grid.
struct Layout {
  std::uint32_t objects = 0;
  std::uint32_t parts = 0;
  float per_metre = 0;  // half cells a metre
  std::uint32_t size() const { return objects + parts; }
};

using Cell = Eigen::Array3i;

// Coordinates (metres, a std::vector<Vector3f>'s floats in a row) in half
// cells (per_metre: half cells a metre), floored: cell h >> 1 on grid 0, (h + 1) >> 1 on grid 1 (floor(v) and
// floor(v + 1/2) for v in cells); kFar for a coordinate that is not finite or
// too far out. Branch-free, for the compiler to vectorize.
void half_cells(const float* coordinates, std::size_t count, float per_metre, int* h) {
  constexpr float kLimit = static_cast<float>(1 << kAxisBits) - 2;
  for (std::size_t i = 0; i < count; ++i) {
    const float x = coordinates[i] * per_metre;
    const auto near = static_cast<std::uint32_t>(-static_cast<std::int32_t>(std::abs(x) < kLimit));  // NaN: 0
    const float y = std::bit_cast<float>(std::bit_cast<std::uint32_t>(x) & near);                   // x or 0
    const int t = static_cast<int>(y);
    const int floor = t - (y < static_cast<float>(t));
    h[i] = static_cast<int>((static_cast<std::uint32_t>(floor) & near) | (static_cast<std::uint32_t>(kFar) & ~near));
  }
}

// Each point's segment: its part if it has one, else its object, kNone for
// none (the objects' cells follow from their parts', expand_objects). True if
// a label exceeds its count. Branch-free, for the compiler to vectorize.
bool point_segments(const std::uint32_t* objects, const std::uint32_t* parts, std::size_t count,
                    const Layout& layout, std::uint32_t* segments) {
  std::uint32_t bad = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t object = objects[i], part = parts ? parts[i] : 0;
    const std::uint32_t segment = part != 0 ? layout.objects + part - 1 : object - 1;
    segments[i] = object != 0 ? segment : kNone;
    bad |= (object > layout.objects) | (part > layout.parts);
  }
  return bad != 0;
}

// A point's cells on both grids packed into sortable keys: the grid bit, then
// the cell relative to `corner` in AxisBits per axis (x-major), then
// segment_bits of room for the segment. With corner -2^20, 21 bits per axis and
// no room: the cell keys of OccupiedCell.
template <int AxisBits>
class CellPacking {
 public:
  CellPacking(const Cell& corner, int segment_bits) : corner_(corner), segment_bits_(segment_bits) {}

  int bits() const { return 3 * AxisBits + 1 + segment_bits_; }
  // The keys of half cells h on grid 0 and grid 1; false if h lies outside the
  // packing's box. Branch-free.
  bool pack(const int* h, std::uint64_t& a, std::uint64_t& b) const {
    const auto x = static_cast<std::uint32_t>((h[0] >> 1) - corner_[0]);  // below the corner: wraps, too large
    const auto y = static_cast<std::uint32_t>((h[1] >> 1) - corner_[1]);
    const auto z = static_cast<std::uint32_t>((h[2] >> 1) - corner_[2]);
    const std::uint64_t cell = std::uint64_t{x} << (2 * AxisBits) | std::uint64_t{y} << AxisBits | z;
    const std::uint64_t up = std::uint64_t(h[0] & 1) << (2 * AxisBits) | std::uint64_t(h[1] & 1) << AxisBits |
                             std::uint64_t(h[2] & 1);  // grid 1: + 1 where the half cell is odd
    a = cell << segment_bits_;
    b = (std::uint64_t{1} << (3 * AxisBits) | (cell + up)) << segment_bits_;
    return std::max({x, y, z}) < (1u << AxisBits) - 1;  // room for grid 1's + 1
  }
  // A key of this packing with its segment as an OccupiedCell.
  OccupiedCell unpack(std::uint64_t key) const {
    constexpr std::uint64_t kAxisMask = (1u << AxisBits) - 1;
    const auto segment = static_cast<std::uint32_t>(key & ((std::uint64_t{1} << segment_bits_) - 1));
    key >>= segment_bits_;
    std::uint64_t cell = (key >> (3 * AxisBits)) << 63;
    for (int k = 0; k < 3; ++k) {
      const auto d = static_cast<int>(key >> ((2 - k) * AxisBits) & kAxisMask);
      cell |= static_cast<std::uint64_t>(d + corner_[k] + (1 << (kAxisBits - 1))) << ((2 - k) * kAxisBits);
    }
    return {cell, segment};
  }

 private:
  Cell corner_;
  int segment_bits_;
};

using FramePacking = CellPacking<kFrameAxisBits>;
using AbsolutePacking = CellPacking<kAxisBits>;

// Finds, chunk by chunk, the labelled points that start a run: whose half
// cells or segment differ from the point before's. Most of the work runs in
// loops the compiler vectorizes; the one scalar loop is branch-free, as which
// points start runs is unpredictable (about every other pixel at 1 m).
class RunScanner {
 public:
  static constexpr std::size_t kChunk = 512;

  RunScanner(const FrameSegments& frame, const Layout& layout)
      : frame_(frame), layout_(layout), parts_(frame.parts ? frame.parts->data() : nullptr) {
    half_.fill(kFar);
    segments_.fill(kNone);
  }

  // Scans points [begin, begin + count), count <= kChunk; throws if a label
  // exceeds its count.
  void scan(std::size_t begin, std::size_t count) {
    std::copy_n(half_.begin() + 3 * last_, 3, half_.begin());  // the point before the chunk
    segments_[0] = segments_[last_];
    objects_ = frame_.objects->data() + begin - 1;  // indexed as half_ and segments_
    half_cells(frame_.points[begin].data(), 3 * count, layout_.per_metre, half_.data() + 3);
    if (point_segments(objects_ + 1, parts_ ? parts_ + begin : nullptr, count, layout_,
                       segments_.data() + 1))
      throw Error("segment tracking: a label above its count");
    for (std::size_t j = 0; j < 3 * count; ++j) changes_[j] = static_cast<std::uint32_t>(half_[j + 3] ^ half_[j]);
    std::size_t picks = 0;
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t changed =
          changes_[3 * i] | changes_[3 * i + 1] | changes_[3 * i + 2] | (segments_[i + 1] ^ segments_[i]);
      picked_[picks] = static_cast<std::uint32_t>(i + 1);
      picks += (changed != 0) & (segments_[i + 1] != kNone);
    }
    picks_ = picks;
    last_ = count;
  }
  std::size_t picks() const { return picks_; }
  // The k-th run start's half cells (kFar: not finite or too far out) and segment.
  const int* half_cells_of(std::size_t k) const { return &half_[3 * picked_[k]]; }
  std::uint32_t segment(std::size_t k) const { return segments_[picked_[k]]; }
  std::uint32_t object(std::size_t k) const { return objects_[picked_[k]] - 1; }

 private:
  const FrameSegments& frame_;
  Layout layout_;
  const std::uint32_t* parts_;
  const std::uint32_t* objects_ = nullptr;  // the chunk's object labels, from entry 1
  // Entry 0 of half_ (3 ints) and segments_: the last point of the chunk before.
  std::array<int, 3 * (kChunk + 1)> half_;
  std::array<std::uint32_t, kChunk + 1> segments_;
  std::array<std::uint32_t, 3 * kChunk> changes_;
  std::array<std::uint32_t, kChunk> picked_;
  std::size_t picks_ = 0, last_ = 0;
};

// Calls emit(a, b, segment, object) for every point of [begin, end) that
// starts a run: its packed cells on both grids, its segment and its object
// (0-based); then chunk_done() after each chunk. False if a point lies outside
// the packing's box.
template <typename Packing, typename Emit, typename ChunkDone>
bool for_each_run(const FrameSegments& frame, const Layout& layout, const Packing& packing, std::size_t begin,
                  std::size_t end, Emit&& emit, ChunkDone&& chunk_done) {
  RunScanner scanner(frame, layout);
  bool inside = true;
  for (std::size_t chunk = begin; chunk < end; chunk += RunScanner::kChunk) {
    scanner.scan(chunk, std::min(RunScanner::kChunk, end - chunk));
    for (std::size_t k = 0; k < scanner.picks(); ++k) {
      const int* h = scanner.half_cells_of(k);
      if (h[0] == kFar || h[1] == kFar || h[2] == kFar) continue;  // labelled, yet no point: bad input
      std::uint64_t a = 0, b = 0;
      inside &= packing.pack(h, a, b);
      emit(a, b, scanner.segment(k), scanner.object(k));
    }
    chunk_done();
  }
  return inside;
}

// Records which object each part lies in: (part, object), 0-based, whenever
// it differs from the last recorded; each part lies in one object.
void record_owner(std::uint32_t segment, std::uint32_t object, const Layout& layout,
                  std::vector<std::pair<std::uint32_t, std::uint32_t>>& owners) {
  if (segment < layout.objects) return;
  const std::pair owner(segment - layout.objects, object);
  if (owners.empty() || owners.back() != owner) owners.push_back(owner);
}

// Drops most repeated keys before the sort: neighbouring pixels, in this row and
// the rows above, mostly share their cells (about 25 pixels a cell at 1 m). A
// direct-mapped cache of recent keys; what it misses, the unique after the sort
// removes. Branch-free.
class RecentKeys {
 public:
  // Appends key to out[size] unless recent; out needs room for one more.
  void add(std::uint64_t key, std::uint64_t* out, std::size_t& size) {
    std::uint64_t& slot = slots_[(key * 0x9E3779B97F4A7C15ull) >> (64 - kBits)];
    const bool fresh = slot != key;
    slot = out[size] = key;
    size += fresh;
  }

 private:
  static constexpr int kBits = 13;  // 64 KB, in L2: the cells of a band of rows
  std::vector<std::uint64_t> slots_ = std::vector<std::uint64_t>(std::size_t{1} << kBits, ~std::uint64_t{0});
};

// What a block of points yields: its packed keys with segment per grid (most
// repeats dropped) and which object each of its parts lies in.
struct BlockKeys {
  std::array<std::vector<std::uint64_t>, 2> keys;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> owners;  // (part, object), 0-based, in point order
  bool fits = false;  // every point inside the packing's box
};

BlockKeys block_keys(const FrameSegments& frame, const Layout& layout, const FramePacking& packing, std::size_t begin,
                     std::size_t end) {
  BlockKeys out;
  for (auto& keys : out.keys) keys.reserve((end - begin) / 4);
  RecentKeys recent;
  std::array<std::array<std::uint64_t, RunScanner::kChunk>, 2> fresh;  // a chunk's keys, at most one a point a grid
  std::array<std::size_t, 2> size{0, 0};
  out.fits = for_each_run(
      frame, layout, packing, begin, end,
      [&](std::uint64_t a, std::uint64_t b, std::uint32_t s, std::uint32_t object) {
        recent.add(a | s, fresh[0].data(), size[0]);
        recent.add(b | s, fresh[1].data(), size[1]);
        record_owner(s, object, layout, out.owners);
      },
      [&] {
        for (int g = 0; g < 2; ++g) {
          out.keys[g].insert(out.keys[g].end(), fresh[g].begin(), fresh[g].begin() + static_cast<std::ptrdiff_t>(size[g]));
          size[g] = 0;
        }
      });
  return out;
}

// block_keys of all points, in parallel over fixed blocks: what a block yields
// depends on the block only, never on the threads (and the sort's unique makes
// the cells independent even of the blocks). False if a point lies outside the
// packing's box; part_object: each part's object.
bool frame_keys(const FrameSegments& frame, const Layout& layout, const FramePacking& packing,
                std::array<std::vector<std::uint64_t>, 2>& keys, std::vector<std::uint32_t>& part_object) {
  constexpr std::size_t kBlock = std::size_t{1} << 15;
  const std::size_t n = frame.points.size(), blocks = (n + kBlock - 1) / kBlock;
  std::vector<BlockKeys> out(blocks);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
    out[k] = block_keys(frame, layout, packing, k * kBlock, std::min(n, (k + 1) * kBlock));
  });
  std::array<std::size_t, 2> total{0, 0};
  for (const BlockKeys& block : out) {
    if (!block.fits) return false;
    for (int g = 0; g < 2; ++g) total[g] += block.keys[g].size();
  }
  for (int g = 0; g < 2; ++g) keys[g].reserve(total[g]);
  for (const BlockKeys& block : out) {
    for (int g = 0; g < 2; ++g) keys[g].insert(keys[g].end(), block.keys[g].begin(), block.keys[g].end());
    for (const auto& [part, object] : block.owners) part_object[part] = object;
  }
  return true;
}

// Adds each object's cells to its parts' (ascending (cell, segment): objects
// and parts, whose points have no part are their objects'): in every cell, the
// objects of the parts there, before the parts.
std::vector<OccupiedCell> expand_objects(const std::vector<OccupiedCell>& cells, const Layout& layout,
                                     const std::vector<std::uint32_t>& part_object) {
  if (layout.parts == 0) return cells;
  const auto object_of = [&](std::uint32_t s) { return s < layout.objects ? s : part_object[s - layout.objects]; };
  std::vector<OccupiedCell> out;
  out.reserve(2 * cells.size());
  std::vector<std::uint32_t> objects;  // of one cell
  for (std::size_t i = 0, end = 0; i < cells.size(); i = end) {
    for (end = i + 1; end < cells.size() && cells[end].cell == cells[i].cell;) ++end;
    if (end == i + 1) {  // most cells hold one segment
      out.push_back({cells[i].cell, object_of(cells[i].segment)});
      if (cells[i].segment >= layout.objects) out.push_back(cells[i]);
      continue;
    }
    objects.clear();
    for (std::size_t j = i; j < end; ++j) objects.push_back(object_of(cells[j].segment));
    std::sort(objects.begin(), objects.end());
    objects.erase(std::unique(objects.begin(), objects.end()), objects.end());
    for (const std::uint32_t object : objects) out.push_back({cells[i].cell, object});
    for (std::size_t j = i; j < end; ++j)
      if (cells[j].segment >= layout.objects) out.push_back(cells[j]);
  }
  return out;
}

// One grid's occupied cells from its frame keys, ascending (cell, segment).
std::vector<OccupiedCell> grid_cells(std::vector<std::uint64_t>& keys, const FramePacking& packing,
                                 const Layout& layout, const std::vector<std::uint32_t>& part_object) {
  // The core's stable radix sort, on the bits below the grid bit (the same in every key).
  detail::radix_sort(keys, detail::PackedKeys{0, packing.bits() - 1});
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<OccupiedCell> cells(keys.size());
  std::transform(keys.begin(), keys.end(), cells.begin(), [&](std::uint64_t k) { return packing.unpack(k); });
  return expand_objects(cells, layout, part_object);
}

// The general path, for frames spread too far for the compact packing: a
// comparison sort of absolute cell keys.
std::array<std::vector<OccupiedCell>, 2> occupied_general(const FrameSegments& frame, const Layout& layout,
                                                      std::vector<std::uint32_t>& part_object) {
  const AbsolutePacking absolute(Cell::Constant(-(1 << (kAxisBits - 1))), 0);
  std::array<std::vector<OccupiedCell>, 2> cells;
  const auto emit = [&](std::uint64_t a, std::uint64_t b, std::uint32_t s, std::uint32_t object) {
    cells[0].push_back({a, s});
    cells[1].push_back({b, s});
    if (s >= layout.objects) part_object[s - layout.objects] = object;
  };
  for_each_run(frame, layout, absolute, 0, frame.points.size(), emit, [] {});
  const auto same = [](const OccupiedCell& a, const OccupiedCell& b) { return a.cell == b.cell && a.segment == b.segment; };
  for (auto& grid : cells) {
    std::sort(grid.begin(), grid.end());
    grid.erase(std::unique(grid.begin(), grid.end(), same), grid.end());
    grid = expand_objects(grid, layout, part_object);
  }
  return cells;
}

// The first labelled point's cell (grid 0), or nothing.
std::optional<Cell> first_cell(const FrameSegments& frame, const Layout& layout) {
  std::array<int, 3> h;
  for (std::size_t i = 0; i < frame.points.size(); ++i) {
    if ((*frame.objects)[i] == 0) continue;
    half_cells(frame.points[i].data(), 3, layout.per_metre, h.data());
    if (h[0] != kFar && h[1] != kFar && h[2] != kFar) return Cell(h[0] >> 1, h[1] >> 1, h[2] >> 1);
  }
  return std::nullopt;
}

// Every segment's occupied cells per grid, ascending (cell, segment);
// part_object: each part's object (kNone: the part has no point).
std::array<std::vector<OccupiedCell>, 2> grids_of(const FrameSegments& frame, const Layout& layout,
                                                    std::vector<std::uint32_t>& part_object) {
  if (frame.points.empty() || frame.objects == nullptr) return {};
  const std::optional<Cell> first = first_cell(frame, layout);
  if (!first) return {};
  const FramePacking packing(*first - (1 << (kFrameAxisBits - 1)), std::bit_width(std::max(layout.size(), 1u) - 1));
  std::array<std::vector<std::uint64_t>, 2> keys;
  if (packing.bits() > 64 || !frame_keys(frame, layout, packing, keys, part_object))
    return occupied_general(frame, layout, part_object);
  std::array<std::vector<OccupiedCell>, 2> cells;
  tbb::parallel_invoke([&] { cells[0] = grid_cells(keys[0], packing, layout, part_object); },
                       [&] { cells[1] = grid_cells(keys[1], packing, layout, part_object); });
  return cells;
}

}  // namespace

OccupiedCells occupied_cells(const FrameSegments& frame, float cell_size) {
  const Layout layout{frame.object_count, frame.parts ? frame.part_count : 0, 2.0f / cell_size};
  OccupiedCells out;
  out.part_object.assign(layout.parts, kNoObject);
  out.grids = grids_of(frame, layout, out.part_object);
  return out;
}

void sort_keys(std::vector<std::uint64_t>& keys, int bits) { detail::radix_sort(keys, detail::PackedKeys{0, bits}); }

std::vector<std::uint32_t> cell_counts(const OccupiedCells& cells, std::uint32_t segment_count) {
  std::vector<std::uint32_t> counts(segment_count, 0);
  for (const auto& grid : cells.grids)
    for (const OccupiedCell& c : grid) ++counts[c.segment];
  return counts;
}

}  // namespace lccp
