#include "lccp/core/voxel_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <limits>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "cell_keys.hpp"
#include "parallel.hpp"
#include "lccp/error.hpp"

namespace lccp {
namespace {

using detail::Cell;
using detail::CellKeys;
using detail::PackedKeys;

constexpr float kMaxCellCoordinate = 1 << 30;  // |cell| beyond this: refuse the cloud
const Cell kInvalidCell = Cell::Constant(std::numeric_limits<int>::min());
// Automatic binning takes a cloud for a camera's when every point lies within
// 60 deg of the +z axis, across and up: a field of view of 120 deg, wider than
// any depth camera's (Kinect v1: 57 x 43 deg). A cloud in a world frame (z up,
// say) spreads beyond it.
constexpr float kViewSlope = 1.7320508f;  // tan(60 deg)

struct CellBounds {
  std::array<int, 3> min{std::numeric_limits<int>::max(), std::numeric_limits<int>::max(),
                         std::numeric_limits<int>::max()};
  std::array<int, 3> max{std::numeric_limits<int>::min(), std::numeric_limits<int>::min(),
                         std::numeric_limits<int>::min()};
  std::size_t count = 0;
  bool outside_view = false;   // a finite point outside the camera's view (camera binning not taken)
  float farthest = 0.0f;       // largest |coordinate| of a finite point

  void add(const Cell& c) {
    for (int a = 0; a < 3; ++a) {
      min[a] = std::min(min[a], c[a]);
      max[a] = std::max(max[a], c[a]);
    }
    ++count;
  }
  void join(const CellBounds& other) {
    for (int a = 0; a < 3; ++a) {
      min[a] = std::min(min[a], other.min[a]);
      max[a] = std::max(max[a], other.max[a]);
    }
    count += other.count;
    outside_view = outside_view || other.outside_view;
    farthest = std::max(farthest, other.farthest);
  }
};

int floor_to_int(float x) {
  if (!(std::abs(x) < kMaxCellCoordinate)) throw Error("the cloud spans too far for its voxel size");
  const int truncated = static_cast<int>(x);
  return truncated - (x < static_cast<float>(truncated));
}

// The cell of a point: cubes of size v, or cells of size v in (x/z, y/z, ln z)
// (PCL's single camera transform), which grow with depth.
Cell cell_of(const Eigen::Vector3f& p, float inverse_size, Binning binning) {
  if (binning == Binning::camera) {
    const float inverse_z = inverse_size / p.z();
    return Cell(floor_to_int(p.x() * inverse_z), floor_to_int(p.y() * inverse_z),
                floor_to_int(std::log(p.z()) * inverse_size));
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

// Cells of every point (kInvalidCell where non-finite or skipped) and their
// bounds, in one pass. Points beyond max_coordinate get no cell; bounds.farthest
// tells. With camera binning, a point outside the view (`slope`) gets no cell; bounds.outside_view tells.
CellBounds compute_cells(const CloudView& cloud, const std::vector<std::uint8_t>& skip, float voxel_size,
                         Binning binning, float slope, float max_coordinate, std::vector<Cell>& cells) {
  cells.resize(cloud.size());
  const float inverse_size = 1.0f / voxel_size;
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, cloud.size()), CellBounds{},
      [&](const auto& range, CellBounds bounds) {
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
          const Eigen::Vector3f& p = cloud.points[i];
          cells[i] = kInvalidCell;
          if (!is_finite(p) || (!skip.empty() && skip[i])) continue;
          bounds.farthest = std::max(bounds.farthest, p.cwiseAbs().maxCoeff());
          if (bounds.farthest > max_coordinate) continue;
          if (binning == Binning::camera && !in_view(p, slope)) {
            bounds.outside_view = true;
            continue;
          }
          cells[i] = cell_of(p, inverse_size, binning);
          bounds.add(cells[i]);
        }
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
  const auto is_valid = [&](std::size_t i) { return cells[i].x() != kInvalidCell.x(); };
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

Eigen::Vector3f unpack_rgb(std::uint32_t rgb) {
  return Eigen::Vector3f(static_cast<float>((rgb >> 16) & 0xff), static_cast<float>((rgb >> 8) & 0xff),
                         static_cast<float>(rgb & 0xff));
}

// Centroid, colour and (if given) normal of every voxel, summed in point order.
void compute_voxel_means(const CloudView& cloud, VoxelGrid& grid) {
  const std::size_t n = grid.points.rows();
  grid.centroids.resize(n);
  grid.colors.assign(n, Eigen::Vector3f::Zero());
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
// (x + dx, y - 1 .. y + 1), consecutive row ids, at z - 1 .. z + 1. Written
// unconditionally into a voxel's 27 slots (26 neighbours and a spare that a
// non-match may overwrite), kept where they match.
void find_neighbors(const std::vector<std::uint64_t>& voxel_keys, const CellKeys& keys, CompressedRows& neighbors) {
  constexpr std::size_t kSlots = 27;
  const std::size_t n = voxel_keys.size();
  const CellRows rows(voxel_keys, keys);
  const std::uint64_t extent_y = keys.extent(1);
  const auto slots = std::make_unique_for_overwrite<std::uint32_t[]>(n * kSlots);
  std::vector<std::uint32_t> counts(n + 1, 0);
  detail::parallel_for_each_index(n, [&](std::size_t v) {
    std::uint32_t* out = slots.get() + v * kSlots;
    std::uint32_t count = 0;
    const std::uint32_t z = rows.z_of(v);
    for (std::uint64_t dx = 0; dx < 3; ++dx) {
      const std::uint64_t first_row = rows.row_of(v) + dx * extent_y - extent_y - 1;
      const std::uint32_t end = rows.first_voxel_from(first_row + 3);
      for (std::uint32_t u = rows.first_voxel_from(first_row); u < end; ++u) {
        out[count] = u;
        count += (rows.z_of(u) + 1 - z <= 2) & (u != v);  // |dz| <= 1, as unsigned
      }
    }
    counts[v + 1] = count;
  });
  neighbors.offsets.resize(n + 1);
  neighbors.offsets[0] = 0;
  for (std::size_t v = 0; v < n; ++v) neighbors.offsets[v + 1] = neighbors.offsets[v] + counts[v + 1];
  neighbors.items.resize(neighbors.offsets[n]);
  detail::parallel_ranges(n, [&](const auto& range) {
    for (std::size_t v = range.begin(); v < range.end(); ++v) {
      std::copy_n(slots.get() + v * kSlots, neighbors.count(v), neighbors.items.data() + neighbors.offsets[v]);
    }
  });
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

VoxelGrid voxelize(const CloudView& cloud, const VoxelConfig& config, const LimitsConfig& limits,
                   const std::vector<std::uint8_t>& skip) {
  check_limit(cloud.size() <= limits.max_points, "the cloud has " + std::to_string(cloud.size()) + " points",
              "max_points", limits.max_points);
  const BinningPlan plan = plan_binning(cloud, config.binning);
  Binning binning = plan.first;
  const float slope = plan.slope;
  std::vector<Cell> cells;
  CellBounds bounds = compute_cells(cloud, skip, config.voxel_size_m, binning, slope, limits.max_coordinate_m, cells);
  check_limit(bounds.farthest <= limits.max_coordinate_m,
              "a point lies " + format_number(bounds.farthest) + " m from the origin along an axis",
              "max_coordinate_m", limits.max_coordinate_m);
  if (bounds.outside_view && !plan.falls_back) {
    throw Error("camera binning needs every point at z > 0; use binning: euclidean");
  }
  if (bounds.outside_view) {
    binning = Binning::euclidean;
    bounds = compute_cells(cloud, skip, config.voxel_size_m, binning, slope, limits.max_coordinate_m, cells);
  }
  if (bounds.count == 0) return no_voxels(cloud, binning);
  const CellKeys keys(Cell(bounds.min[0], bounds.min[1], bounds.min[2]), Cell(bounds.max[0], bounds.max[1], bounds.max[2]));
  const PackedKeys packing = detail::packed_keys(keys, cloud.size());
  if (!keys.fits() || !packing.fits()) throw Error("the cloud spans too many voxels for its voxel size");

  VoxelGrid grid;
  grid.binning = binning;
  std::vector<std::uint64_t> voxel_keys;
  detail::group_runs(sorted_point_keys(cells, keys, packing, bounds.count), packing, voxel_keys, grid.points);
  check_limit(voxel_keys.size() <= limits.max_voxels, "the cloud fills " + std::to_string(voxel_keys.size()) + " voxels",
              "max_voxels", limits.max_voxels);
  compute_voxel_means(cloud, grid);
  find_neighbors(voxel_keys, keys, grid.neighbors);
  return grid;
}

}  // namespace lccp
