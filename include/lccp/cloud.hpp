#pragma once
// Point cloud and label types shared by every stage.
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace lccp {

// Per-point attributes as parallel arrays (structure of arrays).
// Missing measurements are NaN points; they keep their place so that an
// organized (image-shaped) cloud stays organized.
struct PointCloud {
  std::uint32_t width = 0;   // points per row
  std::uint32_t height = 1;  // rows; > 1 means organized
  std::vector<Eigen::Vector3f> points;   // metres, sensor frame; NaN = no data
  std::vector<std::uint32_t> colors;     // packed 0x00RRGGBB; empty if the cloud has none
  std::vector<Eigen::Vector3f> normals;  // unit normals; empty if the cloud has none

  std::size_t size() const { return points.size(); }
  bool organized() const { return height > 1; }
  bool has_colors() const { return !colors.empty(); }
  bool has_normals() const { return !normals.empty(); }
};

// A read-only view of a cloud's arrays: a PointCloud's (it converts
// implicitly), or a caller's own memory (e.g. a numpy array of float32 x, y, z
// triples), read in place. What the segmenter reads; the arrays must outlive
// the view and everything made from it (SegmentationWork).
struct CloudView {
  CloudView() = default;
  CloudView(const PointCloud& cloud)  // NOLINT: implicit, a PointCloud is a cloud
      : width(cloud.width), height(cloud.height), points(cloud.points), colors(cloud.colors),
        normals(cloud.normals) {}

  std::uint32_t width = 0;   // points per row
  std::uint32_t height = 1;  // rows; > 1 means organized
  std::span<const Eigen::Vector3f> points;   // as PointCloud::points
  std::span<const std::uint32_t> colors;     // as PointCloud::colors: empty or one per point
  std::span<const Eigen::Vector3f> normals;  // as PointCloud::normals: empty or one per point

  std::size_t size() const { return points.size(); }
  bool organized() const { return height > 1; }
  bool has_colors() const { return !colors.empty(); }
  bool has_normals() const { return !normals.empty(); }
};

// One label per point, in the cloud's point order. 0 = no label (non-finite point).
using Labels = std::vector<std::uint32_t>;

inline bool is_finite(const Eigen::Vector3f& p) { return p.allFinite(); }

}  // namespace lccp
