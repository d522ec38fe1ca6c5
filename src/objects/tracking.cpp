#include "lccp/objects/tracking.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "../core/cell_keys.hpp"
#include "lccp/error.hpp"

// Matching by overlap of occupied cells. Every segment of a frame is the set of
// cells its points fall in; a segment inherits the id of the previous frame's
// segment its cell set overlaps most, greedily, best overlap first.
//
// Why overlap and not centroid + extent: two objects that touch (a mug standing
// against a box) have centroids a few centimetres apart and overlapping boxes,
// so a centroid rule swaps their ids as soon as one moves, and the centroid of
// a partly occluded object jumps by half its size when a hand covers it. Cell
// sets do neither: touching objects share at most their boundary cells, and the
// visible remainder of an occluded object still lies in the cells it occupied.
//
// Why intersection over union (IoU) and not over the smaller set: at 30 Hz an
// object moves a few millimetres between frames, much less than its size, so it
// overlaps its own previous cells almost entirely, IoU near 1; occlusion grows
// by a few centimetres a frame at most, so even a hand sweeping over an object
// keeps consecutive frames' IoU high. Over the smaller set, every fragment that
// lies inside its predecessor scores 1: when an object splits, its small piece
// would tie with the large one, and a speck of noise where an object vanished
// would inherit its id. IoU ranks the larger piece first and leaves small
// fragments below the threshold.
//
// Merged and split again. The largest surfaces in view (a wall, the floor) meet
// at a seam, and where noise bridges it for a frame or a few, they are one
// object; then they split again. In the merged frame the merged object inherits
// the larger surface's id (the higher IoU) and the smaller one's id is gone, so
// when it splits off it would get a new id, every few frames (the synthetic
// recording's wall, 27 500 points, 3 -> 179 -> 518 -> 908 ...). IoU cannot
// help: the merged object is already taken by the larger surface, and the
// wall's own id is no longer in the previous frame. The geometry is clear
// though: the wall did not move, its cells are inside the merged object's. So a
// previous object that no segment inherited, but of whose cells a current
// object holds at least kMinOverlap (the least share its own successor would
// need), is absorbed: its id and its last cells go with that object (the one
// holding most of them) while it lives; and a later object without an id that
// lies in those cells (IoU >= kMinOverlap, the rule for any match) takes the id
// back. An absorbed id lapses after kAbsorbedFrames (its cells grow stale as
// things move: at 3-5 mm a frame, 30 frames are 10-15 cm) or when its carrier
// is gone; an object that vanished without being absorbed still comes back new.
//
// Speed (a VGA frame: 307,200 points, 10 objects, 100 parts; median 1.6 ms on
// 2 cores, 2.8 ms on 1, of a shared 2-core EPYC VM): cells are sortable 64-bit
// keys, not hash sets. Points are scanned in parallel blocks, in loops the
// compiler vectorizes; a point makes keys only where its cells or segment
// differ from the point before's, and a cache of recent keys drops most
// repeats; the keys of each grid are radix-sorted, and two frames' sorted cells
// are merged in one pass. Only parts make keys: an object's cells are those of
// its parts (and of its points without a part).
namespace lccp {
namespace {

// A segment's occupied cell in one frame: the cell's key (grid, x, y, z) and
// the segment, objects 0..object_count-1 first, then the parts.
struct Occupied {
  std::uint64_t cell = 0;
  std::uint32_t segment = 0;
};

// One frame's segments as the tracker keeps them.
struct TrackedFrame {
  std::array<std::vector<Occupied>, 2> cells;  // per grid: ascending (cell, segment), no repeats
  std::vector<std::uint32_t> sizes;            // per segment: how many cells it occupies, both grids
  std::vector<std::uint32_t> ids;              // per segment: its stable id
  std::vector<std::uint32_t> owner_ids;        // per part: the stable id of its object
  std::uint32_t object_count = 0;
};

// Ids of objects that merged into a neighbour ("Merged and split again" above):
// each as a segment of its own with the cells it had when last seen.
struct AbsorbedIds {
  TrackedFrame segments;                // every segment an object; ids: the absorbed ids
  std::vector<std::uint32_t> carriers;  // per absorbed id: the id of the object that took it in
  std::vector<std::uint32_t> ages;      // per absorbed id: frames since it was absorbed
};

// 1 cm cells: twice and more the 3-5 mm an object moves between frames at 30 Hz
// (so most of its cells stay occupied), and small next to table-top objects
// (5-30 cm: tens of cells across, so the few boundary cells it shares with a
// touching neighbour are a small part of either). Kinect-class depth noise at
// 1-2 m is 2-8 mm, about a cell.
constexpr float kCellSize = 0.01f;
// Two grids, the second shifted by half a cell on every axis, both counted in a
// segment's cells. A flat face square to an axis (a box front seen head-on)
// moving 5 mm along its normal can cross a cell boundary of one grid and leave
// every cell it occupied there; it cannot cross one of each grid in the same
// frame (their boundaries are half a cell apart), so the worst case keeps
// IoU >= 1/3 where one grid would drop to 0. (A 10 cm box moving 2.9 mm along
// each axis, its faces on cell boundaries: with one grid its IoU fell to 0.05
// as all six faces crossed at once, and it lost its id.)
//
// Below this IoU there is no match. The same object in consecutive frames scores
// near 1 (1/3 in the worst case above); a segment that appeared where another
// vanished, or a small piece split off, shares far less.
constexpr double kMinOverlap = 0.25;
// Frames an absorbed id waits with its carrier for a split (1 s at 30 Hz).
constexpr std::uint32_t kAbsorbedFrames = 30;
// Cell keys (OccupiedCell::cell): the grid bit, then 21 bits per axis (x-major):
// |coordinate| < 2^20 cells (10 km); points beyond (no depth sensor measures
// them) are not matched.
constexpr int kAxisBits = 21;
// The sort packs fewer: 12 bits per axis, cells within 2048 (20 m) of the
// frame's first point, as a depth sensor's (range < 10 m) all are; frames that
// spread farther take a slower path.
constexpr int kFrameAxisBits = 12;
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
constexpr int kFar = std::numeric_limits<int>::min();  // a coordinate not finite or too far out

// A frame's segments in one index space: objects 0..objects-1, then the parts.
struct Layout {
  std::uint32_t objects = 0;
  std::uint32_t parts = 0;
  std::uint32_t size() const { return objects + parts; }
};

using Cell = Eigen::Array3i;

// Coordinates (metres, a std::vector<Vector3f>'s floats in a row) in half
// cells, floored: cell h >> 1 on grid 0, (h + 1) >> 1 on grid 1 (floor(v) and
// floor(v + 1/2) for v in cells); kFar for a coordinate that is not finite or
// too far out. Branch-free, for the compiler to vectorize.
void half_cells(const float* coordinates, std::size_t count, int* h) {
  constexpr float kLimit = static_cast<float>(1 << kAxisBits) - 2;
  for (std::size_t i = 0; i < count; ++i) {
    const float x = coordinates[i] * (2.0f / kCellSize);
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
  Occupied unpack(std::uint64_t key) const {
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
    half_cells(frame_.points[begin].data(), 3 * count, half_.data() + 3);
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
std::vector<Occupied> expand_objects(const std::vector<Occupied>& cells, const Layout& layout,
                                     const std::vector<std::uint32_t>& part_object) {
  if (layout.parts == 0) return cells;
  const auto object_of = [&](std::uint32_t s) { return s < layout.objects ? s : part_object[s - layout.objects]; };
  std::vector<Occupied> out;
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
std::vector<Occupied> grid_cells(std::vector<std::uint64_t>& keys, const FramePacking& packing,
                                 const Layout& layout, const std::vector<std::uint32_t>& part_object) {
  // The core's stable radix sort, on the bits below the grid bit (the same in every key).
  detail::radix_sort(keys, detail::PackedKeys{0, packing.bits() - 1});
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<Occupied> cells(keys.size());
  std::transform(keys.begin(), keys.end(), cells.begin(), [&](std::uint64_t k) { return packing.unpack(k); });
  return expand_objects(cells, layout, part_object);
}

bool cell_then_segment(const Occupied& a, const Occupied& b) {
  return a.cell != b.cell ? a.cell < b.cell : a.segment < b.segment;
}

// The general path, for frames spread too far for the compact packing: a
// comparison sort of absolute cell keys.
std::array<std::vector<Occupied>, 2> occupied_general(const FrameSegments& frame, const Layout& layout,
                                                      std::vector<std::uint32_t>& part_object) {
  const AbsolutePacking absolute(Cell::Constant(-(1 << (kAxisBits - 1))), 0);
  std::array<std::vector<Occupied>, 2> cells;
  const auto emit = [&](std::uint64_t a, std::uint64_t b, std::uint32_t s, std::uint32_t object) {
    cells[0].push_back({a, s});
    cells[1].push_back({b, s});
    if (s >= layout.objects) part_object[s - layout.objects] = object;
  };
  for_each_run(frame, layout, absolute, 0, frame.points.size(), emit, [] {});
  const auto same = [](const Occupied& a, const Occupied& b) { return a.cell == b.cell && a.segment == b.segment; };
  for (auto& grid : cells) {
    std::sort(grid.begin(), grid.end(), cell_then_segment);
    grid.erase(std::unique(grid.begin(), grid.end(), same), grid.end());
    grid = expand_objects(grid, layout, part_object);
  }
  return cells;
}

// The first labelled point's cell (grid 0), or nothing.
std::optional<Cell> first_cell(const FrameSegments& frame) {
  std::array<int, 3> h;
  for (std::size_t i = 0; i < frame.points.size(); ++i) {
    if ((*frame.objects)[i] == 0) continue;
    half_cells(frame.points[i].data(), 3, h.data());
    if (h[0] != kFar && h[1] != kFar && h[2] != kFar) return Cell(h[0] >> 1, h[1] >> 1, h[2] >> 1);
  }
  return std::nullopt;
}

// Every segment's occupied cells per grid, ascending (cell, segment);
// part_object: each part's object (kNone: the part has no point).
std::array<std::vector<Occupied>, 2> occupied_cells(const FrameSegments& frame, const Layout& layout,
                                                    std::vector<std::uint32_t>& part_object) {
  if (frame.points.empty() || frame.objects == nullptr) return {};
  const std::optional<Cell> first = first_cell(frame);
  if (!first) return {};
  const FramePacking packing(*first - (1 << (kFrameAxisBits - 1)), std::bit_width(std::max(layout.size(), 1u) - 1));
  std::array<std::vector<std::uint64_t>, 2> keys;
  if (packing.bits() > 64 || !frame_keys(frame, layout, packing, keys, part_object))
    return occupied_general(frame, layout, part_object);
  std::array<std::vector<Occupied>, 2> cells;
  tbb::parallel_invoke([&] { cells[0] = grid_cells(keys[0], packing, layout, part_object); },
                       [&] { cells[1] = grid_cells(keys[1], packing, layout, part_object); });
  return cells;
}

std::vector<std::uint32_t> segment_sizes(const std::array<std::vector<Occupied>, 2>& cells,
                                         std::uint32_t segment_count) {
  std::vector<std::uint32_t> sizes(segment_count, 0);
  for (const auto& grid : cells)
    for (const Occupied& c : grid) ++sizes[c.segment];
  return sizes;
}

void check_labels(const Labels* labels, std::size_t point_count, const char* what) {
  if (labels != nullptr && labels->size() != point_count)
    throw Error(std::string("segment tracking: ") + what + " labels and points differ in number");
}

void check_frame(const FrameSegments& frame) {
  if (frame.object_count > 0 && (frame.points.empty() || frame.objects == nullptr))
    throw Error("segment tracking: object_count > 0 without points or object labels");
  const std::size_t n = frame.points.size();
  check_labels(frame.objects, n, "object");
  check_labels(frame.parts, n, "part");
  if (frame.parts != nullptr && frame.objects == nullptr)
    throw Error("segment tracking: part labels without object labels");
  if (std::uint64_t{frame.object_count} + frame.part_count >= kNone)
    throw Error("segment tracking: too many segments");
}

// A segment of this frame and one of the previous frame, at the same level,
// sharing cells.
struct Candidate {
  std::uint32_t current = 0;
  std::uint32_t previous = 0;
  std::uint32_t previous_id = 0;
  std::uint64_t shared = 0;    // cells in both
  std::uint64_t combined = 0;  // cells in either
};

// Calls count(current, previous) for every cell of a grid that a segment of
// this frame shares with one of the previous frame at the same level.
template <typename Count>
void for_each_shared_cell(const TrackedFrame& now, const TrackedFrame& before, int grid, Count&& count) {
  const Occupied *i = now.cells[grid].data(), *i_last = i + now.cells[grid].size();
  const Occupied *j = before.cells[grid].data(), *j_last = j + before.cells[grid].size();
  while (i != i_last && j != j_last) {
    if (i->cell != j->cell) {
      i->cell < j->cell ? ++i : ++j;
      continue;
    }
    const Occupied *i_end = i + 1, *j_end = j + 1;
    while (i_end != i_last && i_end->cell == i->cell) ++i_end;
    while (j_end != j_last && j_end->cell == j->cell) ++j_end;
    for (const Occupied* a = i; a != i_end; ++a)
      for (const Occupied* b = j; b != j_end; ++b)
        if ((a->segment < now.object_count) == (b->segment < before.object_count)) count(a->segment, b->segment);
    i = i_end;
    j = j_end;
  }
}

// The shared cells of every pair of segments (current * previous count +
// previous) that shares any, ascending: counted in a table per grid (in
// parallel) while that is small (at most 2^20 pairs: 100 parts in each frame
// make 10^4), else as one key per shared cell and pair, radix-sorted (linear in
// the shared cells: a cluttered room's 2 000 segments make 4 * 10^6 pairs).
std::vector<std::pair<std::uint64_t, std::uint64_t>> shared_counts(const TrackedFrame& now,
                                                                   const TrackedFrame& before) {
  const std::uint64_t before_count = before.sizes.size(), pairs = now.sizes.size() * before_count;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> out;
  if (pairs <= (std::uint64_t{1} << 20)) {
    std::array<std::vector<std::uint32_t>, 2> table;
    tbb::parallel_for(0, 2, [&](int g) {
      table[g].assign(pairs, 0);
      for_each_shared_cell(now, before, g, [&](std::uint32_t u, std::uint32_t v) { ++table[g][u * before_count + v]; });
    });
    for (std::uint64_t k = 0; k < pairs; ++k)
      if (table[0][k] + table[1][k] != 0) out.emplace_back(k, table[0][k] + table[1][k]);
    return out;
  }
  std::vector<std::uint64_t> keys;
  for (int g = 0; g < 2; ++g)
    for_each_shared_cell(now, before, g, [&](std::uint32_t u, std::uint32_t v) { keys.push_back(u * before_count + v); });
  detail::radix_sort(keys, detail::PackedKeys{0, static_cast<int>(std::bit_width(pairs - 1))});
  for (std::size_t i = 0, end = 0; i < keys.size(); i = end) {
    for (end = i + 1; end < keys.size() && keys[end] == keys[i];) ++end;
    out.emplace_back(keys[i], end - i);
  }
  return out;
}

using SharedCounts = std::vector<std::pair<std::uint64_t, std::uint64_t>>;  // shared_counts()

// The pairs of segments whose overlap (IoU) reaches kMinOverlap.
std::vector<Candidate> candidates(const TrackedFrame& now, const TrackedFrame& before, const SharedCounts& counts) {
  const std::uint64_t before_count = before.sizes.size();
  std::vector<Candidate> found;
  for (const auto& [pair, shared] : counts) {
    Candidate c{static_cast<std::uint32_t>(pair / before_count), static_cast<std::uint32_t>(pair % before_count), 0,
                shared, 0};
    c.previous_id = before.ids[c.previous];
    c.combined = now.sizes[c.current] + before.sizes[c.previous] - c.shared;
    if (static_cast<double>(c.shared) >= kMinOverlap * static_cast<double>(c.combined)) found.push_back(c);
  }
  return found;
}

// Greedy order: higher IoU first (compared exactly), then the older previous id,
// then the lower current label.
bool better(const Candidate& a, const Candidate& b) {
  using Wide = unsigned __int128;
  const Wide lhs = Wide{a.shared} * b.combined, rhs = Wide{b.shared} * a.combined;
  if (lhs != rhs) return lhs > rhs;
  if (a.previous_id != b.previous_id) return a.previous_id < b.previous_id;
  return a.current < b.current;
}

// Gives each segment the id of its best still-free predecessor; before_taken
// marks the previous frame's segments already inherited.
void match(std::vector<Candidate> found, std::vector<std::uint32_t>& ids, std::vector<char>& before_taken) {
  std::sort(found.begin(), found.end(), better);
  for (const Candidate& c : found) {
    if (ids[c.current] != kNone || before_taken[c.previous]) continue;
    ids[c.current] = c.previous_id;
    before_taken[c.previous] = 1;
  }
}

// Objects first; then parts, each only from a part of the previous object its own
// object inherited from (a part does not jump objects). part_object: 0-based.
void match_levels(std::vector<Candidate> found, const TrackedFrame& now, const TrackedFrame& before,
                  const std::vector<std::uint32_t>& part_object, std::vector<std::uint32_t>& ids,
                  std::vector<char>& before_taken) {
  const auto parts_begin = std::partition(found.begin(), found.end(),
                                          [&](const Candidate& c) { return c.current < now.object_count; });
  std::vector<Candidate> parts(parts_begin, found.end());
  found.erase(parts_begin, found.end());
  match(std::move(found), ids, before_taken);
  std::erase_if(parts, [&](const Candidate& c) {
    const std::uint32_t owner = part_object[c.current - now.object_count];
    return owner == kNone || ids[owner] == kNone || ids[owner] != before.owner_ids[c.previous - before.object_count];
  });
  match(std::move(parts), ids, before_taken);
}

// Objects of this frame still without an id that lie where an absorbed object
// was (IoU >= kMinOverlap with its last cells) take its id back, best first.
void reclaim_absorbed(const AbsorbedIds& absorbed, TrackedFrame& now, std::vector<char>& reclaimed) {
  if (absorbed.segments.ids.empty()) return;
  std::vector<Candidate> found =
      candidates(now, absorbed.segments, shared_counts(now, absorbed.segments));
  std::erase_if(found, [&](const Candidate& c) { return c.current >= now.object_count || now.ids[c.current] != kNone; });
  match(std::move(found), now.ids, reclaimed);
}

// Previous objects that nothing inherited, each with the id of the current
// object holding most of its cells if that is at least kMinOverlap of them:
// (previous object, carrier id), ascending.
std::vector<std::pair<std::uint32_t, std::uint32_t>> absorptions(const TrackedFrame& now, const TrackedFrame& before,
                                                                  const std::vector<char>& before_taken,
                                                                  const SharedCounts& counts) {
  const std::uint64_t before_count = before.sizes.size();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> best(before.object_count, {0, kNone});  // (shared, current)
  for (const auto& [pair, shared] : counts) {
    const auto u = static_cast<std::uint32_t>(pair / before_count), v = static_cast<std::uint32_t>(pair % before_count);
    if (u < now.object_count && v < before.object_count && !before_taken[v] && shared > best[v].first)
      best[v] = {shared, u};
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::uint32_t v = 0; v < before.object_count; ++v) {
    if (best[v].second != kNone && static_cast<double>(best[v].first) >= kMinOverlap * before.sizes[v])
      out.emplace_back(v, now.ids[best[v].second]);
  }
  return out;
}

// The cells of the chosen segments of `from` (segment -> its new index, kNone:
// not chosen) per grid, ascending: a monotone renumbering keeps the order.
std::array<std::vector<Occupied>, 2> chosen_cells(const TrackedFrame& from, const std::vector<std::uint32_t>& index) {
  std::array<std::vector<Occupied>, 2> out;
  if (std::all_of(index.begin(), index.end(), [](std::uint32_t i) { return i == kNone; })) return out;
  for (int g = 0; g < 2; ++g)
    for (const Occupied& c : from.cells[g])
      if (index[c.segment] != kNone) out[g].push_back({c.cell, index[c.segment]});
  return out;
}

// The absorbed ids that go on: those kept (by `keep`: the new carrier id, kNone
// to drop) of `old`, one frame older, then the new absorptions of `before`'s
// objects at age 0.
AbsorbedIds next_absorbed(const AbsorbedIds& old, const std::vector<std::uint32_t>& keep,
                                  const TrackedFrame& before,
                                  const std::vector<std::pair<std::uint32_t, std::uint32_t>>& absorbed_now) {
  AbsorbedIds next;
  std::vector<std::uint32_t> old_index(old.segments.ids.size(), kNone), new_index(before.ids.size(), kNone);
  const auto add = [&](std::uint32_t id, std::uint32_t size, std::uint32_t carrier, std::uint32_t age) {
    next.segments.ids.push_back(id);
    next.segments.sizes.push_back(size);
    next.carriers.push_back(carrier);
    next.ages.push_back(age);
    return static_cast<std::uint32_t>(next.segments.ids.size() - 1);
  };
  for (std::size_t e = 0; e < keep.size(); ++e)
    if (keep[e] != kNone) old_index[e] = add(old.segments.ids[e], old.segments.sizes[e], keep[e], old.ages[e] + 1);
  for (const auto& [v, carrier] : absorbed_now) new_index[v] = add(before.ids[v], before.sizes[v], carrier, 0);
  next.segments.object_count = static_cast<std::uint32_t>(next.segments.ids.size());
  const auto kept_cells = chosen_cells(old.segments, old_index), new_cells = chosen_cells(before, new_index);
  for (int g = 0; g < 2; ++g) {
    next.segments.cells[g].resize(kept_cells[g].size() + new_cells[g].size());
    std::merge(kept_cells[g].begin(), kept_cells[g].end(), new_cells[g].begin(), new_cells[g].end(),
               next.segments.cells[g].begin(), cell_then_segment);
  }
  return next;
}

// What becomes of the absorbed ids after this frame: an id not taken back goes
// on with its carrier while the carrier is in this frame (or with the object
// that absorbed the carrier itself) and it is younger than kAbsorbedFrames;
// previous objects absorbed now join.
AbsorbedIds carry_absorbed(const AbsorbedIds& old, const std::vector<char>& reclaimed,
                                   const TrackedFrame& now, const TrackedFrame& before,
                                   const std::vector<char>& before_taken, const SharedCounts& counts) {
  const auto absorbed_now = absorptions(now, before, before_taken, counts);
  std::vector<std::uint32_t> alive(now.ids.begin(), now.ids.begin() + now.object_count);
  std::sort(alive.begin(), alive.end());
  std::vector<std::uint32_t> keep(old.segments.ids.size(), kNone);
  for (std::size_t e = 0; e < keep.size(); ++e) {
    if (reclaimed[e] || old.ages[e] + 1 >= kAbsorbedFrames) continue;
    const std::uint32_t carrier = old.carriers[e];
    if (std::binary_search(alive.begin(), alive.end(), carrier)) keep[e] = carrier;
    for (const auto& [v, new_carrier] : absorbed_now)
      if (before.ids[v] == carrier) keep[e] = new_carrier;
  }
  return next_absorbed(old, keep, before, absorbed_now);
}

}  // namespace

struct SegmentTracker::History {
  TrackedFrame previous;  // what the next frame is matched against
  AbsorbedIds absorbed;   // ids merged into a previous object, which a split gives back
};

SegmentTracker::SegmentTracker(std::uint32_t first_id) : next_id_(first_id), history_(std::make_unique<History>()) {}
SegmentTracker::~SegmentTracker() = default;
SegmentTracker::SegmentTracker(SegmentTracker&&) noexcept = default;
SegmentTracker& SegmentTracker::operator=(SegmentTracker&&) noexcept = default;

TrackedIds SegmentTracker::update(const FrameSegments& frame) {
  check_frame(frame);
  const Layout layout{frame.object_count, frame.parts ? frame.part_count : 0};
  std::vector<std::uint32_t> part_object(layout.parts, kNone);
  TrackedFrame now;
  now.cells = occupied_cells(frame, layout, part_object);
  now.sizes = segment_sizes(now.cells, layout.size());
  now.object_count = layout.objects;
  now.ids.assign(layout.size(), kNone);
  std::vector<char> before_taken(history_->previous.ids.size(), 0);
  const SharedCounts counts = shared_counts(now, history_->previous);
  match_levels(candidates(now, history_->previous, counts), now, history_->previous, part_object, now.ids, before_taken);
  std::vector<char> reclaimed(history_->absorbed.segments.ids.size(), 0);
  reclaim_absorbed(history_->absorbed, now, reclaimed);

  TrackedIds out;
  for (std::uint32_t& id : now.ids) {
    if (id != kNone) continue;
    if (next_id_ == kNone) throw Error("segment tracking: the ids are used up");
    out.new_ids.push_back(id = next_id_++);
  }
  for (std::size_t v = 0; v < before_taken.size(); ++v)
    if (!before_taken[v]) out.gone_ids.push_back(history_->previous.ids[v]);
  std::sort(out.gone_ids.begin(), out.gone_ids.end());
  for (const std::uint32_t owner : part_object) now.owner_ids.push_back(owner == kNone ? kNone : now.ids[owner]);
  out.object_ids.assign(now.ids.begin(), now.ids.begin() + layout.objects);
  out.part_ids.assign(now.ids.begin() + layout.objects, now.ids.end());
  history_->absorbed = carry_absorbed(history_->absorbed, reclaimed, now, history_->previous, before_taken, counts);
  history_->previous = std::move(now);
  return out;
}

}  // namespace lccp
