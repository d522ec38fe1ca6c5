#pragma once
// What the synthetic sensor looks at: where the camera stands, the table, the
// floor and wall behind it, and the objects on the table with their motion over
// one period. World frame: z up, the table top at z = 0, the camera looking
// along +y and down at the table centre from about 1 m.
#include <array>
#include <cstdint>

#include <Eigen/Core>

#include "lccp/synthetic/tabletop_scene.hpp"

namespace lccp::synthetic::detail {

// Every motion repeats after kPeriodFrames frames (10 s at 30 Hz).
inline constexpr std::uint64_t kPeriodFrames = 300;

// The mug: a cup (outer wall, open top, inner wall and bottom) and a handle,
// a tube bent in a half circle in the cup's local x-z plane: one object, two
// parts (labels object_label(kMugObject, kBodyPart) and (kMugObject, kHandlePart)).
inline constexpr double kMugOuterRadiusM = 0.045;
inline constexpr double kMugInnerRadiusM = 0.039;
inline constexpr double kMugHeightM = 0.10;
inline constexpr double kMugBottomM = 0.008;      // thickness of the bottom
inline constexpr double kHandleArcRadiusM = 0.03;  // centre line
inline constexpr double kHandleTubeRadiusM = 0.005;
inline constexpr std::size_t kHandleSegments = 6;  // capsules along the arc

// Background planes (world): the floor under the table and the wall behind it.
inline constexpr double kFloorZ = -0.74;
inline constexpr double kWallY = 1.2;

struct CameraPose {
  Eigen::Vector3d position;  // world, metres
  Eigen::Matrix3d axes;      // columns: the optical x (right), y (down), z (forward) axes in world
};
CameraPose camera_pose();

// A plane n . p + offset = 0 with unit normal n, p in metres.
struct Plane {
  Eigen::Vector3d normal;
  double offset = 0;
};

// The table top in the camera's optical frame (the frame of back_project's
// points), normal pointing up, out of the table.
Plane table_plane_in_camera();

enum class Shape {
  box,         // [-x, x] x [-y, y] x [0, z] of `size`
  cylinder,    // radius size.x(), height size.z(), base disc at z = 0
  cup,         // the mug's body (kMug* constants)
  handle,      // the mug's handle (kHandle* constants), in the cup's frame
};

// One rigid solid: its shape in a local frame (z up), placed by a translation
// and a rotation about the vertical axis.
struct Part {
  Shape shape = Shape::box;
  std::uint32_t label = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // world, of the local origin
  double yaw_rad = 0;                                  // about world z
  Eigen::Vector3d size = Eigen::Vector3d::Zero();      // box half sizes x, y and height; cylinder radius, -, height
  Eigen::Vector3d local_min = Eigen::Vector3d::Zero(); // bounds of the solid in the local frame
  Eigen::Vector3d local_max = Eigen::Vector3d::Zero();
};

// The table: a slab whose top is the plane z = 0.
Part table();

// The objects' parts at time t_s (seconds; periodic): objects 1..kObjectCount
// in order, each one part labelled object_label(n), the mug as two parts
// labelled object_label(kMugObject, kBodyPart) and object_label(kMugObject,
// kHandlePart), its handle last.
inline constexpr std::size_t kPartCount = kObjectCount + 1;
std::array<Part, kPartCount> object_parts_at(double t_s);

// The handle's centre line in the cup's frame: kHandleSegments + 1 points.
std::array<Eigen::Vector3d, kHandleSegments + 1> handle_centre_line();

}  // namespace lccp::synthetic::detail
