#include "lccp/core/voxel_grid.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <string>
#include <limits>
#include <memory>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include "cell_keys.hpp"
#include "parallel.hpp"
#include "lccp/error.hpp"

namespace lccp {
namespace {

using detail::Cell;
using detail::CellKeys;
using detail::PackedKeys;

constexpr float kMaxCellCoordinate = 1 << 30;  // |cell| beyond this: refuse the cloud
constexpr int kNoCell = std::numeric_limits<int>::min();
const Cell kInvalidCell = Cell::Constant(kNoCell);

bool has_cell(const Cell& cell) { return cell.x() != kNoCell; }
// Automatic binning takes a cloud for a camera's when every point lies within
// 60 deg of the +z axis, across and up: a field of view of 120 deg, wider than
// any depth camera's (Kinect v1: 57 x 43 deg). A cloud in a world frame (z up,
// say) spreads beyond it.
constexpr float kViewSlope = 1.7320508f;  // tan(60 deg)

struct CellBounds {
  Cell min = Cell::Constant(std::numeric_limits<int>::max());
  Cell max = Cell::Constant(std::numeric_limits<int>::min());
  std::size_t count = 0;
  bool outside_view = false;   // a finite point outside the camera's view (camera binning not taken)
  float farthest = 0.0f;       // largest |coordinate| of a finite point

  void join(const CellBounds& other) {
    min = min.min(other.min);
    max = max.max(other.max);
    count += other.count;
    outside_view = outside_view || other.outside_view;
    farthest = std::max(farthest, other.farthest);
  }
};

[[noreturn]] void throw_too_far() { throw Error("the cloud spans too far for its voxel size"); }

// Inlined (three calls a point): its throw is out of line.
int floor_to_int(float x) {
  if (!(std::abs(x) < kMaxCellCoordinate)) throw_too_far();
  const int truncated = static_cast<int>(x);
  return truncated - (x < static_cast<float>(truncated));
}

// The depth coordinate of camera cells, in cells: ln z / v (PCL's camera
// transform; a cell is v z deep), or with SensorConfig::depth_steps
// never shallower than the sensor's depth step q z^2: beyond z_q = v / q it
// goes on as ln(z_q) / v + (1 / z_q - 1 / z) / q, whose slope 1 / (q z^2) is
// one cell per step. Measurable depths are z_n = 1 / (n q) (Khoshelham and
// Elberink 2012), so there neighbouring ones lie exactly one cell apart.
class DepthAxis {
 public:
  DepthAxis(float voxel_size, const SensorConfig& sensor)
      : inverse_size_(1.0f / voxel_size),
        step_from_(sensor.depth_steps && sensor.step_per_m2() > 0.0f ? voxel_size / sensor.step_per_m2()
                                                               : std::numeric_limits<float>::infinity()),
        inverse_step_(1.0f / sensor.step_per_m2()),
        at_step_from_(std::log(step_from_) * inverse_size_ + inverse_step_ / step_from_) {}

  float inverse_size() const { return inverse_size_; }
  float operator()(float z) const {
    return z <= step_from_ ? std::log(z) * inverse_size_ : at_step_from_ - inverse_step_ / z;
  }

 private:
  float inverse_size_;  // 1 / v
  float step_from_;     // z_q; infinite: ln z / v at every depth
  float inverse_step_;  // 1 / q
  float at_step_from_;  // ln(z_q) / v + 1 / (q z_q)
};

// floor(depth coordinate), remembered per depth: a depth camera's depths take
// few distinct values (a Kinect frame of mOSD: under 400 among 170 000
// points), so a small direct-mapped table of the depths seen (Fibonacci
// hashing of their bits, Knuth TAOCP vol. 3, 6.4) spares most logarithms. A
// depth's level is computed as before, only not again.
class DepthLevels {
 public:
  explicit DepthLevels(const DepthAxis& axis) : axis_(axis) { slots_.fill({kNoDepth, 0}); }

  int level(float z) {
    const auto bits = std::bit_cast<std::uint32_t>(z);
    Slot& slot = slots_[(bits * 0x9e3779b1u) >> (32 - kSlotBits)];
    if (slot.bits != bits) slot = {bits, floor_to_int(axis_(z))};
    return slot.level;
  }

 private:
  static constexpr int kSlotBits = 10;
  static constexpr std::uint32_t kNoDepth = 0xffffffffu;  // a NaN's bits: no point's depth
  struct Slot {
    std::uint32_t bits;
    int level;
  };
  std::array<Slot, std::size_t{1} << kSlotBits> slots_;
  DepthAxis axis_;
};

// The cell of a point: cubes of size v, or cells of size v in (x/z, y/z, ln z)
// (PCL's single camera transform), which grow with depth.
Cell cell_of(const Eigen::Vector3f& p, float inverse_size, Binning binning, DepthLevels& levels) {
  if (binning == Binning::camera) {
    const float inverse_z = inverse_size / p.z();
    return Cell(floor_to_int(p.x() * inverse_z), floor_to_int(p.y() * inverse_z), levels.level(p.z()));
  }
  return Cell(floor_to_int(p.x() * inverse_size), floor_to_int(p.y() * inverse_size),
              floor_to_int(p.z() * inverse_size));
}

// Whether a camera at the origin looking along +z sees p: in front of it and
// within `slope` (tan of half the field of view) of its axis, across and up.
bool in_view(const Eigen::Vector3f& p, float slope) {
  return p.z() > 0.0f && std::abs(p.x()) <= slope * p.z() && std::abs(p.y()) <= slope * p.z();
}

// The binning to try first, how wide a view the camera transform takes (tan of
// half the field of view), and whether a point outside it means cubes (else
// an error). Automatic binning tries the camera transform on any cloud (it
// needs no image grid) and falls back to cubes if a point lies outside a
// camera's view; `organized` is PCL's rule, the camera transform for organized
// clouds in front of the sensor; asked for, the camera transform needs only z > 0.
struct BinningPlan {
  Binning first;
  float slope;
  bool falls_back;
};

BinningPlan plan_binning(const CloudView& cloud, Binning requested) {
  constexpr float kAnySlope = std::numeric_limits<float>::infinity();
  switch (requested) {
    case Binning::automatic: return {Binning::camera, kViewSlope, true};
    case Binning::organized: return {cloud.organized() ? Binning::camera : Binning::euclidean, kAnySlope, true};
    case Binning::camera: return {Binning::camera, kAnySlope, false};
    case Binning::euclidean: break;
  }
  return {Binning::euclidean, kAnySlope, false};
}

// What compute_cells reads, as values: its loops keep them in registers.
struct CellJob {
  const Eigen::Vector3f* points;
  const std::uint8_t* skip;  // null: none skipped
  float inverse_size;
  Binning binning;
  DepthAxis depth;  // camera cells' depth coordinate
  float slope;  // camera cells: tan of half the field of view taken
  float max_coordinate;
};

// The cells of points [begin, end) (kInvalidCell where non-finite or skipped,
// beyond max_coordinate, or outside the view for camera cells), and their
// bounds. The bounds are kept in scalars: GCC keeps Eigen arrays in memory.
CellBounds cells_of_points(const CellJob job, std::size_t begin, std::size_t end, Cell* cells) {
  DepthLevels levels(job.depth);
  CellBounds bounds;
  std::array<int, 3> low = {bounds.min.x(), bounds.min.y(), bounds.min.z()};
  std::array<int, 3> high = {bounds.max.x(), bounds.max.y(), bounds.max.z()};
  float farthest = 0.0f;
  for (std::size_t i = begin; i < end; ++i) {
    const Eigen::Vector3f& p = job.points[i];
    Cell cell = kInvalidCell;
    if (is_finite(p) && !(job.skip && job.skip[i])) {
      farthest = std::max(farthest, p.cwiseAbs().maxCoeff());
      const bool outside = job.binning == Binning::camera && !in_view(p, job.slope);
      bounds.outside_view |= outside && farthest <= job.max_coordinate;
      if (farthest <= job.max_coordinate && !outside) cell = cell_of(p, job.inverse_size, job.binning, levels);
    }
    cells[i] = cell;
    if (!has_cell(cell)) continue;
    for (int a = 0; a < 3; ++a) {
      low[a] = std::min(low[a], cell[a]);
      high[a] = std::max(high[a], cell[a]);
    }
    ++bounds.count;
  }
  bounds.min = Cell(low[0], low[1], low[2]);
  bounds.max = Cell(high[0], high[1], high[2]);
  bounds.farthest = farthest;
  return bounds;
}

// Cells of every point (kInvalidCell where non-finite or skipped) and their
// bounds, in one pass. Points beyond max_coordinate get no cell; bounds.farthest
// tells. With camera binning, a point outside the view (`slope`) gets no cell; bounds.outside_view tells.
CellBounds compute_cells(const CloudView& cloud, const std::vector<std::uint8_t>& skip, Binning binning,
                         const DepthAxis& depth, float slope, float max_coordinate, std::vector<Cell>& cells) {
  cells.resize(cloud.size());
  const CellJob job{cloud.points.data(), skip.empty() ? nullptr : skip.data(), depth.inverse_size(), binning, depth,
                    slope, max_coordinate};
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, cloud.size()), CellBounds{},
      [&](const auto& range, CellBounds bounds) {
        bounds.join(cells_of_points(job, range.begin(), range.end(), cells.data()));
        return bounds;
      },
      [](CellBounds a, const CellBounds& b) {
        a.join(b);
        return a;
      },
      tbb::static_partitioner());
}

// Finite points as packed (cell key, point index), sorted by key; points of
// one cell stay in index order. Compacted in parallel over fixed blocks.
std::vector<std::uint64_t> sorted_point_keys(const std::vector<Cell>& cells, const CellKeys& keys,
                                             const PackedKeys& packing, std::size_t finite_count) {
  constexpr std::size_t kBlock = std::size_t{1} << 14;
  const std::size_t blocks = (cells.size() + kBlock - 1) / kBlock;
  const auto is_valid = [&](std::size_t i) { return has_cell(cells[i]); };
  std::vector<std::size_t> first_slot(blocks + 1, 0);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    for (std::size_t i = b * kBlock; i < std::min(cells.size(), (b + 1) * kBlock); ++i) first_slot[b + 1] += is_valid(i);
  });
  for (std::size_t b = 0; b < blocks; ++b) first_slot[b + 1] += first_slot[b];
  std::vector<std::uint64_t> values(finite_count);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::size_t slot = first_slot[b];
    for (std::size_t i = b * kBlock; i < std::min(cells.size(), (b + 1) * kBlock); ++i) {
      if (is_valid(i)) values[slot++] = packing.pack(keys.key(cells[i]), static_cast<std::uint32_t>(i));
    }
  });
  detail::radix_sort(values, packing);
  return values;
}

// A box with at most this many (x, y) rows of cells per finite point is
// grouped by a counting sort over its rows (camera cells, table-top scenes);
// wider boxes by the radix sort.
constexpr std::uint64_t kRowsPerPointForCounting = 2;
constexpr std::size_t kChunkPoints = std::size_t{1} << 16;  // fewest points per chunk
constexpr std::size_t kChunkVoxels = std::size_t{1} << 12;  // fewest voxels per chunk

// Chunks of items for loops whose chunks each keep state of their own (counts
// per row, lists): one per thread, each of at least min_items (any split
// gives the same result).
std::size_t thread_chunks(std::size_t items, std::size_t min_items) {
  const auto threads = static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency()));
  return std::clamp<std::size_t>(items / min_items, 1, threads);
}

// Finite points as packed (place along z, point index), stably sorted by
// (x, y) row of cells (a counting sort: count per row and chunk, prefix sum in
// (row, chunk) order, scatter). row_first[r] is where row r begins.
std::unique_ptr<std::uint64_t[]> points_by_row(const std::vector<Cell>& cells, const CellKeys& keys,
                                               const PackedKeys& packing, std::size_t finite_count,
                                               std::vector<std::uint32_t>& row_first) {
  const std::size_t rows = keys.extent(0) * keys.extent(1), chunks = thread_chunks(cells.size(), kChunkPoints);
  const auto chunk_range = [&](std::size_t c) {
    return tbb::blocked_range<std::size_t>(cells.size() * c / chunks, cells.size() * (c + 1) / chunks);
  };
  std::vector<std::uint32_t> next(chunks * rows, 0);  // per chunk, per row
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    std::uint32_t* count = next.data() + c * rows;
    const CellKeys own_keys = keys;  // a local copy: the stores below cannot alias it
    const auto range = chunk_range(c);
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      if (has_cell(cells[i])) ++count[own_keys.row(cells[i])];
    }
  });
  row_first.resize(rows + 1);
  std::uint32_t running = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    row_first[r] = running;
    for (std::size_t c = 0; c < chunks; ++c) running += std::exchange(next[c * rows + r], running);
  }
  row_first[rows] = running;
  auto values = std::make_unique_for_overwrite<std::uint64_t[]>(finite_count);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    std::uint32_t* slot = next.data() + c * rows;
    std::uint64_t* out = values.get();
    const CellKeys own_keys = keys;  // local copies: the stores below cannot alias them
    const PackedKeys own_packing = packing;
    const auto range = chunk_range(c);
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      if (!has_cell(cells[i])) continue;
      out[slot[own_keys.row(cells[i])]++] = own_packing.pack(own_keys.level(cells[i]), static_cast<std::uint32_t>(i));
    }
  });
  return values;
}

// A row's points come nearly sorted (a camera cell's points mostly share one
// depth cell): an insertion sort, or std::sort for a long row.
void sort_row(std::uint64_t* first, std::uint64_t* last) {
  constexpr std::ptrdiff_t kInsertionSortLength = 32;
  if (last - first > kInsertionSortLength) {
    std::sort(first, last);
    return;
  }
  for (std::uint64_t* i = first + (first != last); i < last; ++i) {
    const std::uint64_t value = *i;
    std::uint64_t* j = i;
    for (; j > first && *(j - 1) > value; --j) *j = *(j - 1);
    *j = value;
  }
}

// Runs of equal place along z in rows [first_row, last_row): each row's points
// sorted by place along z (then index), their indices written to item, each
// run's cell key and first position appended to run_keys and run_first.
void group_rows(std::uint64_t* values, const std::vector<std::uint32_t>& row_first, std::size_t first_row,
                std::size_t last_row, PackedKeys packing, std::uint64_t extent_z, std::uint32_t* item,
                std::vector<std::uint64_t>& run_keys, std::vector<std::uint32_t>& run_first) {
  for (std::size_t r = first_row; r < last_row; ++r) {
    const std::uint32_t first = row_first[r], last = row_first[r + 1];
    sort_row(values + first, values + last);
    std::uint64_t previous = ~std::uint64_t{0};
    for (std::uint32_t i = first; i < last; ++i) {
      const std::uint64_t level = packing.key(values[i]);
      if (level != previous) {
        run_keys.push_back(r * extent_z + level);
        run_first.push_back(i);
        previous = level;
      }
      item[i] = packing.index(values[i]);
    }
  }
}

// The points grouped into voxels, in parallel over shares of the rows with
// about equal numbers of points; the first share writes into the results,
// the others' runs are appended to them.
void group_voxels(std::uint64_t* values, const std::vector<std::uint32_t>& row_first, const PackedKeys& packing,
                  std::uint64_t extent_z, std::vector<std::uint64_t>& run_keys, CompressedRows& members) {
  const std::size_t n = row_first.back(), rows = row_first.size() - 1, shares = thread_chunks(n, kChunkPoints);
  std::vector<std::size_t> share_row(shares + 1, rows);
  for (std::size_t s = 0; s < shares; ++s) {
    share_row[s] = std::lower_bound(row_first.begin(), row_first.end() - 1, n * s / shares) - row_first.begin();
  }
  members.items.resize(n);
  run_keys.clear();
  members.offsets.clear();
  std::vector<std::vector<std::uint64_t>> keys(shares);
  std::vector<std::vector<std::uint32_t>> firsts(shares);
  tbb::parallel_for(std::size_t{0}, shares, [&](std::size_t s) {
    group_rows(values, row_first, share_row[s], share_row[s + 1], packing, extent_z, members.items.data(),
               s == 0 ? run_keys : keys[s], s == 0 ? members.offsets : firsts[s]);
  });
  for (std::size_t s = 1; s < shares; ++s) {
    run_keys.insert(run_keys.end(), keys[s].begin(), keys[s].end());
    members.offsets.insert(members.offsets.end(), firsts[s].begin(), firsts[s].end());
  }
  members.offsets.push_back(static_cast<std::uint32_t>(n));
}

// Finite points grouped into voxels: run_keys the voxels' cell keys,
// ascending; members their points, in index order.
void group_points(const std::vector<Cell>& cells, const CellKeys& keys, std::size_t finite_count,
                  std::vector<std::uint64_t>& run_keys, CompressedRows& members) {
  const PackedKeys packing = detail::packed_keys(keys, cells.size());
  if (keys.extent(0) * keys.extent(1) > kRowsPerPointForCounting * finite_count) {
    detail::group_runs(sorted_point_keys(cells, keys, packing, finite_count), packing, run_keys, members);
    return;
  }
  const PackedKeys by_level{packing.index_bits, static_cast<int>(std::bit_width(keys.extent(2) - 1))};
  std::vector<std::uint32_t> row_first;
  const auto values = points_by_row(cells, keys, by_level, finite_count, row_first);
  group_voxels(values.get(), row_first, by_level, keys.extent(2), run_keys, members);
}

Eigen::Vector3f unpack_rgb(std::uint32_t rgb) {
  return Eigen::Vector3f(static_cast<float>((rgb >> 16) & 0xff), static_cast<float>((rgb >> 8) & 0xff),
                         static_cast<float>(rgb & 0xff));
}

// Centroid, colour and (if given) normal of every voxel, summed in point order.
void compute_voxel_means(const CloudView& cloud, VoxelGrid& grid) {
  const std::size_t n = grid.points.rows();
  grid.centroids.resize(n);
  grid.colors.resize(n);  // every voxel's is written below
  if (cloud.has_normals()) grid.mean_normals.resize(n);
  grid.voxel_of_point.assign(cloud.size(), kNoVoxel);
  detail::parallel_ranges(n, [&](const auto& range) {
    for (std::size_t v = range.begin(); v < range.end(); ++v) {
      Eigen::Vector3d xyz = Eigen::Vector3d::Zero(), rgb = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
      for (const std::uint32_t* p = grid.points.begin(v); p != grid.points.end(v); ++p) {
        grid.voxel_of_point[*p] = static_cast<std::uint32_t>(v);
        xyz += cloud.points[*p].cast<double>();
        if (cloud.has_colors()) rgb += unpack_rgb(cloud.colors[*p]).cast<double>();
        if (cloud.has_normals() && cloud.normals[*p].allFinite()) normal += cloud.normals[*p].cast<double>();
      }
      const double count = grid.points.count(v);
      grid.centroids[v] = (xyz / count).cast<float>();
      grid.colors[v] = (rgb / count).cast<float>();
      if (cloud.has_normals()) {
        grid.mean_normals[v] = (normal.norm() > 0.0 ? Eigen::Vector3d(normal.normalized()) : Eigen::Vector3d::Zero()).cast<float>();
      }
    }
  });
}

// Voxels sorted by key come grouped by (x, y) row of cells, ordered by z
// within a row. Per voxel its row id (x * extent_y + y) and z, and for any row
// id the first voxel at or after it: a dense table when the box has few rows
// for its voxels (camera cells, table-top scenes), else a search of the
// occupied rows.
class CellRows {
 public:
  CellRows(const std::vector<std::uint64_t>& voxel_keys, const CellKeys& keys)
      : row_of_(voxel_keys.size()), z_of_(voxel_keys.size()) {
    const std::uint64_t extent_z = keys.extent(2);
    detail::parallel_for_each_index(voxel_keys.size(), [&](std::size_t v) {
      row_of_[v] = voxel_keys[v] / extent_z;
      z_of_[v] = static_cast<std::uint32_t>(voxel_keys[v] - row_of_[v] * extent_z);
    });
    const std::uint64_t rows = keys.extent(0) * keys.extent(1);
    if (rows <= kDenseRowsPerVoxel * voxel_keys.size() + kDenseRowsAlways) {
      first_.assign(rows + 1, 0);  // voxels per row, then an exclusive prefix sum
      for (const std::uint64_t row : row_of_) ++first_[row + 1];
      for (std::uint64_t r = 0; r < rows; ++r) first_[r + 1] += first_[r];
    } else {
      for (std::uint32_t v = 0; v < row_of_.size(); ++v) {
        if (occupied_.empty() || row_of_[v] != occupied_.back()) {
          occupied_.push_back(row_of_[v]);
          first_.push_back(v);
        }
      }
      first_.push_back(static_cast<std::uint32_t>(row_of_.size()));
    }
  }

  std::uint64_t row_of(std::size_t v) const { return row_of_[v]; }
  std::uint32_t z_of(std::size_t v) const { return z_of_[v]; }
  std::uint32_t first_voxel_from(std::uint64_t row) const {
    if (occupied_.empty()) return first_[row];
    return first_[std::lower_bound(occupied_.begin(), occupied_.end(), row) - occupied_.begin()];
  }

 private:
  static constexpr std::uint64_t kDenseRowsPerVoxel = 8;
  static constexpr std::uint64_t kDenseRowsAlways = std::uint64_t{1} << 20;
  std::vector<std::uint64_t> row_of_;
  std::vector<std::uint32_t> z_of_;
  std::vector<std::uint64_t> occupied_;  // sparse case: occupied row ids, ascending
  std::vector<std::uint32_t> first_;     // dense: per row id; sparse: per occupied row; + voxel count
};

// 26-neighbourhood: the neighbours of a voxel in row (x, y) lie in the rows
// (x + dx, y - 1 .. y + 1), consecutive row ids, at z - 1 .. z + 1. Each
// candidate is written unconditionally at the end of the chunk's list and
// kept (the end moves on) where it matches; v's own rows are scanned on
// either side of v.
std::uint32_t scan_neighbors(const CellRows& rows, std::uint64_t extent_y, std::size_t v, std::uint32_t* out) {
  std::uint32_t count = 0;
  const std::uint32_t z_low = rows.z_of(v) - 1;
  const auto scan = [&](std::uint32_t first, std::uint32_t end) {
    for (std::uint32_t u = first; u < end; ++u) {
      out[count] = u;
      count += rows.z_of(u) - z_low <= 2;  // |dz| <= 1, as unsigned
    }
  };
  for (std::uint64_t dx = 0; dx < 3; ++dx) {
    const std::uint64_t first_row = rows.row_of(v) + dx * extent_y - extent_y - 1;
    const std::uint32_t first = rows.first_voxel_from(first_row), end = rows.first_voxel_from(first_row + 3);
    if (dx != 1) {
      scan(first, end);
    } else {  // v's own rows: all but v
      scan(first, static_cast<std::uint32_t>(v));
      scan(static_cast<std::uint32_t>(v) + 1, end);
    }
  }
  return count;
}

// The neighbour rows, in parallel over one chunk of voxels per thread: each
// chunk lists its voxels' neighbours one after the other in a buffer of its
// own (room for 26 and a spare that a non-match may overwrite, per voxel);
// the lists are then appended to the rows.
void find_neighbors(const std::vector<std::uint64_t>& voxel_keys, const CellKeys& keys, CompressedRows& neighbors) {
  constexpr std::size_t kSlots = 27;
  const std::size_t n = voxel_keys.size(), chunks = thread_chunks(n, kChunkVoxels);
  const CellRows rows(voxel_keys, keys);
  const auto chunk_begin = [&](std::size_t c) { return n * c / chunks; };
  std::vector<std::unique_ptr<std::uint32_t[]>> lists(chunks);
  neighbors.offsets.resize(n + 1);
  neighbors.offsets[0] = 0;
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    lists[c] = std::make_unique_for_overwrite<std::uint32_t[]>((chunk_begin(c + 1) - chunk_begin(c)) * kSlots);
    std::uint32_t* out = lists[c].get();
    for (std::size_t v = chunk_begin(c); v < chunk_begin(c + 1); ++v) {
      neighbors.offsets[v + 1] = scan_neighbors(rows, keys.extent(1), v, out);
      out += neighbors.offsets[v + 1];
    }
  });
  for (std::size_t v = 0; v < n; ++v) neighbors.offsets[v + 1] += neighbors.offsets[v];
  neighbors.items.clear();
  neighbors.items.reserve(neighbors.offsets[n]);  // appended, not zero-filled first
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::uint32_t length = neighbors.offsets[chunk_begin(c + 1)] - neighbors.offsets[chunk_begin(c)];
    neighbors.items.insert(neighbors.items.end(), lists[c].get(), lists[c].get() + length);
  }
}

std::string format_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

void check_limit(bool ok, const std::string& what, const char* key, double limit) {
  if (!ok) throw Error(what + ", more than " + key + " (" + format_number(limit) + ")");
}

// A cloud whose finite points were all left out (outside the region of
// interest, or on the support plane: an empty table) has nothing to segment,
// which is a result, not an error; one without any finite point is an error.
VoxelGrid no_voxels(const CloudView& cloud, Binning binning) {
  if (std::none_of(cloud.points.begin(), cloud.points.end(), is_finite)) throw Error("the cloud has no finite points");
  VoxelGrid grid;
  grid.binning = binning;
  grid.points.offsets.assign(1, 0);
  grid.neighbors.offsets.assign(1, 0);
  grid.voxel_of_point.assign(cloud.size(), kNoVoxel);
  return grid;
}

}  // namespace

VoxelGrid voxelize(const CloudView& cloud, const VoxelConfig& config, const SensorConfig& sensor,
                   const LimitsConfig& limits, const std::vector<std::uint8_t>& skip) {
  check_limit(cloud.size() <= limits.max_points, "the cloud has " + std::to_string(cloud.size()) + " points",
              "max_points", limits.max_points);
  const BinningPlan plan = plan_binning(cloud, config.binning);
  Binning binning = plan.first;
  const float slope = plan.slope;
  std::vector<Cell> cells;
  const DepthAxis depth(config.voxel_size_m, sensor);
  CellBounds bounds = compute_cells(cloud, skip, binning, depth, slope, limits.max_coordinate_m, cells);
  check_limit(bounds.farthest <= limits.max_coordinate_m,
              "a point lies " + format_number(bounds.farthest) + " m from the origin along an axis",
              "max_coordinate_m", limits.max_coordinate_m);
  if (bounds.outside_view && !plan.falls_back) {
    throw Error("camera binning needs every point at z > 0; use binning: euclidean");
  }
  if (bounds.outside_view) {
    binning = Binning::euclidean;
    bounds = compute_cells(cloud, skip, binning, depth, slope, limits.max_coordinate_m, cells);
  }
  if (bounds.count == 0) return no_voxels(cloud, binning);
  const CellKeys keys(bounds.min, bounds.max);
  if (!keys.fits() || !detail::packed_keys(keys, cloud.size()).fits()) throw Error("the cloud spans too many voxels for its voxel size");

  VoxelGrid grid;
  grid.binning = binning;
  std::vector<std::uint64_t> voxel_keys;
  group_points(cells, keys, bounds.count, voxel_keys, grid.points);
  check_limit(voxel_keys.size() <= limits.max_voxels, "the cloud fills " + std::to_string(voxel_keys.size()) + " voxels",
              "max_voxels", limits.max_voxels);
  compute_voxel_means(cloud, grid);
  find_neighbors(voxel_keys, keys, grid.neighbors);
  return grid;
}

}  // namespace lccp
