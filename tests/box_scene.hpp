#pragma once
// Boxes of known size and pose standing on a plane, for tests of per-segment
// geometry. World frame: z up, the plane z = 0. The sensor sits at the origin of
// its own frame (x right, y down, z forward) and looks down at the scene; all the
// truth is given in the sensor frame. The visible parts of the box faces and of a
// square of the plane are sampled on a grid (2 mm, edges included): an
// unorganized, noise-free cloud. `render(scene.rects)` (test_clouds.hpp) gives
// an organized variant by ray casting, `rect_truth` its per-rect truth.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lccp/core/support_plane.hpp"
#include "test_clouds.hpp"

namespace lccp::test {

// A box on the plane: footprint centre (x, y), yaw about z, full edge lengths
// along its own x, y, z (world metres and degrees).
struct BoxSpec {
  double x = 0, y = 0, yaw_deg = 0;
  Eigen::Vector3d size = Eigen::Vector3d::Constant(0.1);
};

// The sensor `distance_m` from `target` (world), `elevation_deg` above the
// plane, in the horizontal direction `azimuth_deg` (from world +x) seen from the target.
struct SensorSpec {
  Eigen::Vector3d target{0, 0, 0.05};
  double distance_m = 0.9, elevation_deg = 45, azimuth_deg = -90;
};

struct BoxTruth {
  Eigen::Vector3d center;   // sensor frame
  Eigen::Matrix3d axes;     // columns: the box's own x, y, z (z up), sensor frame
  Eigen::Vector3d extents;  // full edge lengths along the axes
};

struct BoxScene {
  PointCloud cloud;             // unorganized
  std::vector<int> truth;       // per point: 0 plane, b + 1 for box b
  std::vector<BoxTruth> boxes;
  Plane plane;                  // normal toward the sensor, d > 0
  std::vector<Rect> rects;      // the plane square and the box faces but the bottom
  std::vector<int> rect_truth;  // per rect, as `truth`
};

namespace detail {
// Whether the segment t p, t in [0, t_max], meets the box grown by `margin` (slab test).
inline bool segment_meets_box(const Eigen::Vector3d& p, double t_max, const BoxTruth& box, double margin) {
  const Eigen::Vector3d o = -box.axes.transpose() * box.center, d = box.axes.transpose() * p;
  double t0 = 0, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    const double h = box.extents[a] / 2 + margin;
    if (std::abs(d[a]) < 1e-15) {
      if (std::abs(o[a]) > h) return false;
      continue;
    }
    const double ta = (-h - o[a]) / d[a], tb = (h - o[a]) / d[a];
    t0 = std::max(t0, std::min(ta, tb)), t1 = std::min(t1, std::max(ta, tb));
  }
  return t0 <= t1;
}

// Grid points of `r` that no box hides: the ray from the sensor must not enter its
// own box, nor another box shrunk by 1 um (points on a contact line stay visible).
inline void sample_visible(const Rect& r, int truth, double step_m, BoxScene& scene) {
  const int nu = static_cast<int>(std::ceil(r.u.norm() / step_m));
  const int nv = static_cast<int>(std::ceil(r.v.norm() / step_m));
  for (int i = 0; i <= nu; ++i) {
    for (int j = 0; j <= nv; ++j) {
      const Eigen::Vector3d p = r.corner + r.u * (double(i) / nu) + r.v * (double(j) / nv);
      bool hidden = false;
      for (std::size_t b = 0; b < scene.boxes.size() && !hidden; ++b) {
        const bool own = static_cast<int>(b) + 1 == truth;
        hidden = segment_meets_box(p, own ? 1 - 1e-6 : 1.0, scene.boxes[b], own ? 0.0 : -1e-6);
      }
      if (!hidden) scene.cloud.points.push_back(p.cast<float>()), scene.truth.push_back(truth);
    }
  }
}
}  // namespace detail

inline BoxScene box_scene(const std::vector<BoxSpec>& specs, const SensorSpec& sensor = {}, double plane_side_m = 0.5,
                          double step_m = 0.002) {
  const double el = deg2rad(sensor.elevation_deg), az = deg2rad(sensor.azimuth_deg);
  const Eigen::Vector3d toward_sensor(std::cos(az) * std::cos(el), std::sin(az) * std::cos(el), std::sin(el));
  const Pose pose = look_at(sensor.target + sensor.distance_m * toward_sensor, sensor.target);
  BoxScene scene;
  scene.plane.normal = (pose.R * Eigen::Vector3d::UnitZ()).cast<float>();
  scene.plane.d = static_cast<float>(-(pose.R * Eigen::Vector3d::UnitZ()).dot(pose.t));
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d ground(sensor.target.x(), sensor.target.y(), 0);
  scene.rects.push_back(pose.apply(centered_rect(ground, X, plane_side_m, Y, plane_side_m)));
  scene.rect_truth.push_back(0);
  for (std::size_t b = 0; b < specs.size(); ++b) {
    const BoxSpec& s = specs[b];
    const Eigen::Matrix3d R = Eigen::AngleAxisd(deg2rad(s.yaw_deg), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d c(s.x, s.y, s.size.z() / 2);
    scene.boxes.push_back({pose.apply(c), pose.R * R, s.size});
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d e1 = R.col((a + 1) % 3), e2 = R.col((a + 2) % 3);
      const double l1 = s.size[(a + 1) % 3], l2 = s.size[(a + 2) % 3];
      for (int sign = a == 2 ? 1 : -1; sign <= 1; sign += 2) {  // no bottom face
        scene.rects.push_back(pose.apply(centered_rect(c + sign * s.size[a] / 2 * R.col(a), e1, l1, e2, l2)));
        scene.rect_truth.push_back(static_cast<int>(b) + 1);
      }
    }
  }
  for (std::size_t r = 0; r < scene.rects.size(); ++r) {
    detail::sample_visible(scene.rects[r], scene.rect_truth[r], step_m, scene);
  }
  scene.cloud.width = static_cast<std::uint32_t>(scene.cloud.points.size());
  return scene;
}

// Box A, 10 x 8 x 12 cm at yaw 30 deg, and box B, 6 x 15 x 7 cm at yaw 120 deg,
// B's 6 x 7 end face against the middle of A's +x face: the part of A's +x face
// above and beside B meets B's top and long sides in concave creases. Seen from
// 0.9 m, 45 deg above the plane, from between A's +x and -y sides, so A's top,
// +x and -y faces and B's top, long -y side and free end are visible.
inline BoxScene two_touching_boxes() {
  const double yaw = 30, c = std::cos(deg2rad(yaw)), s = std::sin(deg2rad(yaw));
  const BoxSpec a{0, 0, yaw, {0.10, 0.08, 0.12}};
  const BoxSpec b{0.125 * c, 0.125 * s, yaw + 90, {0.06, 0.15, 0.07}};
  SensorSpec sensor;
  sensor.target = {0.06 * c, 0.06 * s, 0.05};
  sensor.azimuth_deg = yaw - 50;
  return box_scene({a, b}, sensor);
}

}  // namespace lccp::test
