#pragma once
// Per-segment geometry for a grasp planner (paper Sec. III.C: "the pose of the
// handle was calculated from its 3D shape"): size, pose, extent and the kind of
// boundary each segment shares with its neighbours.
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "lccp/core/lccp.hpp"
#include "lccp/core/support_plane.hpp"

namespace lccp {

// Lengths in metres in the input cloud's frame.
struct OrientedBox {
  Eigen::Vector3f center = Eigen::Vector3f::Zero();
  Eigen::Matrix3f axes = Eigen::Matrix3f::Identity();  // columns: unit axes, right-handed
  Eigen::Vector3f extents = Eigen::Vector3f::Zero();   // full edge lengths along each axis
};

enum class Boundary : std::uint8_t { convex, concave };
enum class Grasp : std::uint8_t { top, side };

struct Neighbour {
  std::uint32_t id = 0;
  Boundary boundary = Boundary::concave;
  friend bool operator==(const Neighbour&, const Neighbour&) = default;
};

struct SegmentGeometry {
  std::uint32_t id = 0;        // the segment's label (dense 1..K, or its stable id once tracked)
  std::uint64_t points = 0;    // member points
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  OrientedBox obb;
  Eigen::Matrix3f principal_axes = Eigen::Matrix3f::Identity();  // columns, largest variance first
  Eigen::Vector3f principal_extents = Eigen::Vector3f::Zero();   // full extent of the points along each
  Eigen::Vector3f mean_normal = Eigen::Vector3f::Zero();         // unit
  Grasp grasp = Grasp::top;
  std::vector<Neighbour> adjacent;  // ascending id
};

// Segments 1..count of a segmented cloud: per point and per supervoxel its
// segment (0: none). The work's own (work.result.labels and
// segment_of_supervoxel), or unions of them (objects grouped from parts).
struct SegmentLabels {
  const Labels& points;
  const std::vector<std::uint32_t>& supervoxels;
  std::uint32_t count = 0;
};

// The geometry of segments 1..K of a segmented cloud, in label order. With a
// support plane the box's third axis is the plane normal and the grasp
// compares the main axis with it; without one the box follows the principal
// axes and "up" is the sensor's -y. Needs the work's grid, normals,
// supervoxels and edges (all stages run).
std::vector<SegmentGeometry> describe_segments(const SegmentationWork& work, const SegmentLabels& segments,
                                               const std::optional<Plane>& support);
// The work's own segments (work.result.labels, K = work.result.segment_count).
std::vector<SegmentGeometry> describe_segments(const SegmentationWork& work, const std::optional<Plane>& support);

}  // namespace lccp
