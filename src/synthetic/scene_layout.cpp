#include "scene_layout.hpp"

#include <cmath>
#include <numbers>

#include "lccp/synthetic/tabletop_scene.hpp"

namespace lccp::synthetic::detail {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kPeriodS = 10.0;
static_assert(kPeriodS * kFrameRateHz == static_cast<double>(kPeriodFrames));
constexpr double kOmega = 2 * kPi / kPeriodS;

// The camera 0.6 m above the table top and 0.8 m in front of its centre,
// tilted 37 deg down: its optical axis meets the table centre at 1.0 m.
constexpr double kCameraHeightM = 0.6;
constexpr double kCameraBackM = 0.8;
constexpr double kCameraTiltRad = 37.0 * kPi / 180.0;

// Objects sized and placed like the mOSD table-top scenes (6-20 cm, 0.9-1.2 m
// away). Positions are of the footprint centre on the table top, x right, y away.
constexpr double kBoxAHalfX = 0.08, kBoxAHalfY = 0.05, kBoxAHeight = 0.12;
constexpr double kBoxAX = -0.25, kBoxAY = 0.08;
constexpr double kBoxBHalfX = 0.045, kBoxBHalfY = 0.035, kBoxBHeight = 0.15;
constexpr double kBoxBX = 0.22, kBoxBY = 0.13;
// Lower than box A: where the two touch, their tops are not one plane (LCCP
// would rightly merge two coplanar tops).
constexpr double kCanRadius = 0.033, kCanHeight = 0.09;
constexpr double kBottleRadius = 0.035, kBottleHeight = 0.19;
constexpr double kBottleY = -0.14, kBottleSwingM = 0.30;
constexpr double kMugX = 0.03, kMugY = 0.0;

Eigen::Matrix3d yaw_rotation(double yaw_rad) {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  Eigen::Matrix3d r;
  r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}

Part box(std::uint32_t label, const Eigen::Vector3d& position, double yaw_rad, double half_x, double half_y,
         double height) {
  Part p;
  p.shape = Shape::box;
  p.label = label;
  p.position = position;
  p.yaw_rad = yaw_rad;
  p.size = Eigen::Vector3d(half_x, half_y, height);
  p.local_min = Eigen::Vector3d(-half_x, -half_y, 0);
  p.local_max = p.size;
  return p;
}

Part cylinder(std::uint32_t label, const Eigen::Vector3d& position, double radius, double height) {
  Part p;
  p.shape = Shape::cylinder;
  p.label = label;
  p.position = position;
  p.size = Eigen::Vector3d(radius, radius, height);
  p.local_min = Eigen::Vector3d(-radius, -radius, 0);
  p.local_max = p.size;
  return p;
}

// Where the handle's arc is centred, just outside the cup's wall, and how far
// it bends round (a little past a half circle, so its ends sink into the wall
// without reaching the inside).
constexpr double kHandleCentreX = kMugOuterRadiusM + 0.002;
constexpr double kHandleHalfAngleRad = 95.0 * kPi / 180.0;

}  // namespace

CameraPose camera_pose() {
  const double c = std::cos(kCameraTiltRad), s = std::sin(kCameraTiltRad);
  CameraPose pose;
  pose.position = Eigen::Vector3d(0, -kCameraBackM, kCameraHeightM);
  pose.axes.col(0) = Eigen::Vector3d(1, 0, 0);   // right
  pose.axes.col(1) = Eigen::Vector3d(0, -s, -c); // down in the image
  pose.axes.col(2) = Eigen::Vector3d(0, c, -s);  // forward
  return pose;
}

Plane table_plane_in_camera() {
  // n_w . p_w = 0 with p_w = R p_c + c: (R^T n_w) . p_c + n_w . c = 0.
  const CameraPose pose = camera_pose();
  const Eigen::Vector3d up(0, 0, 1);
  return Plane{pose.axes.transpose() * up, up.dot(pose.position)};
}

Part table() {
  // 1.5 m x 1.2 m, 3 cm thick, its far edge 1.3 m from the camera's foot.
  return box(kTableLabel, Eigen::Vector3d(0, -0.1, -0.03), 0.0, 0.75, 0.6, 0.03);
}

std::array<Part, kPartCount> object_parts_at(double t_s) {
  const double phase = kOmega * t_s;
  const double s = std::sin(phase), c = std::cos(phase);

  // Box A turns back and forth by +-20 deg.
  const double box_a_yaw = 0.35 + 0.35 * s;
  // The can rides against box A's short face, sliding along it and moving
  // away by up to 2 cm: in contact at t = 5 s.
  const Eigen::Vector3d can_in_box_a(kBoxAHalfX + kCanRadius + 0.01 * (1 + c), 0.02 * s, 0);
  const Eigen::Vector3d box_a_position(kBoxAX, kBoxAY, 0);
  const Eigen::Vector3d can_position = box_a_position + yaw_rotation(box_a_yaw) * can_in_box_a;
  // The bottle swings left and right in front of everything (passes in front
  // of the mug at 2.5 s and 7.5 s, of box A and the can around 5 s).
  const Eigen::Vector3d bottle_position(kBottleSwingM * c, kBottleY, 0);

  std::array<Part, kPartCount> parts;
  parts[0] = box(object_label(1), box_a_position, box_a_yaw, kBoxAHalfX, kBoxAHalfY, kBoxAHeight);
  // Box B turns once per period.
  parts[1] = box(object_label(2), Eigen::Vector3d(kBoxBX, kBoxBY, 0), 0.3 + phase, kBoxBHalfX, kBoxBHalfY,
                 kBoxBHeight);
  parts[2] = cylinder(object_label(3), can_position, kCanRadius, kCanHeight);
  parts[3] = cylinder(object_label(4), bottle_position, kBottleRadius, kBottleHeight);

  // The mug turns once per period, its handle sweeping round.
  Part cup;
  cup.shape = Shape::cup;
  cup.label = object_label(kMugObject, kBodyPart);
  cup.position = Eigen::Vector3d(kMugX, kMugY, 0);
  cup.yaw_rad = -0.5 + phase;
  cup.local_min = Eigen::Vector3d(-kMugOuterRadiusM, -kMugOuterRadiusM, 0);
  cup.local_max = Eigen::Vector3d(kMugOuterRadiusM, kMugOuterRadiusM, kMugHeightM);
  // The handle is a part of its own (OSD/mOSD label the parts of an object
  // n * 10 + k), so that scoring can tell whether it was split off the body.
  Part handle = cup;
  handle.shape = Shape::handle;
  handle.label = object_label(kMugObject, kHandlePart);
  const double reach = kHandleArcRadiusM + kHandleTubeRadiusM;
  handle.local_min = Eigen::Vector3d(kMugOuterRadiusM - 0.01, -kHandleTubeRadiusM, kMugHeightM / 2 - reach);
  handle.local_max = Eigen::Vector3d(kHandleCentreX + reach, kHandleTubeRadiusM, kMugHeightM / 2 + reach);
  parts[4] = cup;
  parts[5] = handle;
  return parts;
}

std::array<Eigen::Vector3d, kHandleSegments + 1> handle_centre_line() {
  std::array<Eigen::Vector3d, kHandleSegments + 1> points;
  for (std::size_t k = 0; k <= kHandleSegments; ++k) {
    const double angle = -kHandleHalfAngleRad + 2 * kHandleHalfAngleRad * static_cast<double>(k) / kHandleSegments;
    points[k] = Eigen::Vector3d(kHandleCentreX + kHandleArcRadiusM * std::cos(angle), 0,
                                kMugHeightM / 2 + kHandleArcRadiusM * std::sin(angle));
  }
  return points;
}

}  // namespace lccp::synthetic::detail
