#pragma once
// Synthetic point clouds for the unit tests.
//
// Scenes are made of flat parallelograms ("rects") and rendered by an ideal pinhole
// camera at the origin looking along +z (x right, y down), with the intrinsics of the
// Kinect-class sensor the mOSD scenes come from: fx = fy = 525 px, 640 x 480. Every pixel
// casts one ray; the nearest rect it hits gives the point, pixels that hit nothing are
// NaN. The result is an organized cloud, cropped to the pixel window that sees the
// scene, so sampling density (about 1.9 mm between points at 1 m) and organisation are
// those of a real depth image, without noise: every point lies on its rect up to float
// rounding, which lets tests compare against analytic planes.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lccp/cloud.hpp"

namespace lccp::test {

// True if a and b put the same points together (the same partition, any ids):
// a stream's stable ids against one cloud's labels 1..K.
inline bool same_partition(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
  if (a.size() != b.size()) return false;
  std::map<std::uint32_t, std::uint32_t> a_to_b, b_to_a;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a_to_b.emplace(a[i], b[i]).first->second != b[i]) return false;
    if (b_to_a.emplace(b[i], a[i]).first->second != a[i]) return false;
  }
  return true;
}

inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

inline double deg2rad(double deg) { return deg * std::numbers::pi / 180.0; }
inline double rad2deg(double rad) { return rad * 180.0 / std::numbers::pi; }

// Angle between two directions in degrees (double precision, clamped).
inline double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double c = a.normalized().dot(b.normalized());
  return rad2deg(std::acos(std::clamp(c, -1.0, 1.0)));
}
inline double angle_deg(const Eigen::Vector3f& a, const Eigen::Vector3d& b) {
  return angle_deg(Eigen::Vector3d(a.cast<double>()), b);
}

// A flat parallelogram: corner + a u + b v for a, b in [0, 1].
struct Rect {
  Eigen::Vector3d corner;
  Eigen::Vector3d u;
  Eigen::Vector3d v;

  Eigen::Vector3d normal() const { return u.cross(v).normalized(); }
  Eigen::Vector3d center() const { return corner + 0.5 * u + 0.5 * v; }
  // The same rect after p -> R p + t.
  Rect transformed(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) const {
    return Rect{R * corner + t, R * u, R * v};
  }
};

// A rect centred at `center` with unit side directions `axis_u`, `axis_v` and side
// lengths `len_u`, `len_v`.
inline Rect centered_rect(const Eigen::Vector3d& center, const Eigen::Vector3d& axis_u, double len_u,
                          const Eigen::Vector3d& axis_v, double len_v) {
  const Eigen::Vector3d u = axis_u.normalized() * len_u;
  const Eigen::Vector3d v = axis_v.normalized() * len_v;
  return Rect{center - 0.5 * u - 0.5 * v, u, v};
}

struct PinholeCamera {
  double focal_px = 525.0;
  double cx = 319.5;
  double cy = 239.5;
  int width = 640;
  int height = 480;
};

// Which rect every point of a rendered cloud came from (-1 for NaN points).
struct RenderedScene {
  PointCloud cloud;
  std::vector<int> rect_of_point;
};

// Ray casting, see the file comment. Crops the image to the bounding window of the
// pixels that hit a rect (the cloud stays organized: width x height of that window).
inline RenderedScene render(const std::vector<Rect>& rects, const PinholeCamera& cam = {}) {
  const int W = cam.width, H = cam.height;
  std::vector<Eigen::Vector3d> hit(static_cast<std::size_t>(W) * H);
  std::vector<int> which(hit.size(), -1);
  int c0 = W, c1 = -1, r0 = H, r1 = -1;
  for (int row = 0; row < H; ++row) {
    for (int col = 0; col < W; ++col) {
      const Eigen::Vector3d ray((col - cam.cx) / cam.focal_px, (row - cam.cy) / cam.focal_px, 1.0);
      double best_t = std::numeric_limits<double>::infinity();
      int best = -1;
      for (std::size_t k = 0; k < rects.size(); ++k) {
        const Rect& r = rects[k];
        const Eigen::Vector3d n = r.u.cross(r.v);
        const double denom = ray.dot(n);
        if (std::abs(denom) < 1e-12) continue;
        const double t = r.corner.dot(n) / denom;
        if (!(t > 0) || t >= best_t) continue;
        const Eigen::Vector3d q = t * ray - r.corner;
        // Solve q = a u + b v in the least-squares sense (q lies in the plane).
        const double uu = r.u.dot(r.u), uv = r.u.dot(r.v), vv = r.v.dot(r.v);
        const double qu = q.dot(r.u), qv = q.dot(r.v);
        const double det = uu * vv - uv * uv;
        const double a = (qu * vv - qv * uv) / det;
        const double b = (qv * uu - qu * uv) / det;
        if (a < 0 || a > 1 || b < 0 || b > 1) continue;
        best_t = t;
        best = static_cast<int>(k);
      }
      if (best < 0) continue;
      const std::size_t i = static_cast<std::size_t>(row) * W + col;
      hit[i] = best_t * ray;
      which[i] = best;
      c0 = std::min(c0, col), c1 = std::max(c1, col);
      r0 = std::min(r0, row), r1 = std::max(r1, row);
    }
  }
  RenderedScene scene;
  if (c1 < 0) return scene;  // nothing visible: empty cloud
  scene.cloud.width = static_cast<std::uint32_t>(c1 - c0 + 1);
  scene.cloud.height = static_cast<std::uint32_t>(r1 - r0 + 1);
  for (int row = r0; row <= r1; ++row) {
    for (int col = c0; col <= c1; ++col) {
      const std::size_t i = static_cast<std::size_t>(row) * W + col;
      if (which[i] < 0) {
        scene.cloud.points.emplace_back(kNaN, kNaN, kNaN);
      } else {
        scene.cloud.points.push_back(hit[i].cast<float>());
      }
      scene.rect_of_point.push_back(which[i]);
    }
  }
  return scene;
}

// --- scenes ---------------------------------------------------------------------------

// A fronto-parallel square of side `side_m` centred on the optical axis at depth z_m:
// the plane z = z_m, facing the sensor (its normal toward the sensor is (0, 0, -1)).
inline Rect fronto_parallel_rect(double z_m, double side_m) {
  return centered_rect({0, 0, z_m}, Eigen::Vector3d::UnitX(), side_m, Eigen::Vector3d::UnitY(), side_m);
}

// The square above rotated about its own centre: first by yaw_deg about the y-axis, then
// by pitch_deg about the x-axis.
inline Rect tilted_rect(double z_m, double side_m, double yaw_deg, double pitch_deg) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(deg2rad(pitch_deg), Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(deg2rad(yaw_deg), Eigen::Vector3d::UnitY()))
                                .toRotationMatrix();
  return centered_rect({0, 0, z_m}, R * Eigen::Vector3d::UnitX(), side_m, R * Eigen::Vector3d::UnitY(), side_m);
}

// Unit normal of a rect oriented toward the sensor at the origin.
inline Eigen::Vector3d normal_toward_sensor(const Rect& r) {
  Eigen::Vector3d n = r.normal();
  if (n.dot(r.corner) > 0) n = -n;  // the origin lies on the side -corner points to
  return n;
}

// An "L": a table and a wall meeting at a 90 deg concave edge, seen from the front by a
// camera tilted 45 deg down. In the camera frame the edge is the line through
// (0, 0, edge_depth_m) along x; the wall rises from it toward the camera along
// (0, -1, -1)/sqrt2 (up), the table comes toward the camera along (0, 1, -1)/sqrt2 (down).
// Each leg is leg_m long and width_m wide. Normals toward the sensor:
// wall (0, 1, -1)/sqrt2, table (0, -1, -1)/sqrt2 - the inside of the corner faces the camera.
struct ConcaveCorner {
  Rect wall;   // rect 0
  Rect table;  // rect 1
  Eigen::Vector3d edge_point;
  Eigen::Vector3d edge_direction;  // unit
  // Distance of p from the edge line.
  double distance_to_edge(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = p - edge_point;
    return (q - q.dot(edge_direction) * edge_direction).norm();
  }
  // 0 for the wall side (y < 0), 1 for the table side.
  int side(const Eigen::Vector3d& p) const { return p.y() < edge_point.y() ? 0 : 1; }
};

namespace detail {
// Two 90 deg legs meeting at the line through (0, 0, edge_depth_m) along x, going
// along (0, -1, toward)/sqrt2 and (0, 1, toward)/sqrt2 with toward = -1 (to the camera) or +1.
inline ConcaveCorner corner(double edge_depth_m, double leg_m, double width_m, double toward) {
  const double s = std::numbers::sqrt2 / 2;
  ConcaveCorner c;
  c.edge_point = {0, 0, edge_depth_m};
  c.edge_direction = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d along_x(width_m, 0, 0);
  const Eigen::Vector3d start = c.edge_point - 0.5 * along_x;
  c.wall = Rect{start, along_x, Eigen::Vector3d(0, -s, toward * s) * leg_m};
  c.table = Rect{start, along_x, Eigen::Vector3d(0, s, toward * s) * leg_m};
  return c;
}
}  // namespace detail

inline ConcaveCorner concave_corner(double edge_depth_m = 1.0, double leg_m = 0.10, double width_m = 0.20) {
  return detail::corner(edge_depth_m, leg_m, width_m, -1.0);
}

// The convex counterpart: a 90 deg ridge pointing at the camera (the L seen from behind).
inline ConcaveCorner convex_ridge(double edge_depth_m = 0.9, double leg_m = 0.10, double width_m = 0.20) {
  return detail::corner(edge_depth_m, leg_m, width_m, +1.0);
}

// A camera-from-world transform for a camera at `eye` looking at `target`, with the
// world's +z up in the image (camera x right, y down, z forward).
struct Pose {
  Eigen::Matrix3d R;  // rows: camera axes in world coordinates
  Eigen::Vector3d t;
  Eigen::Vector3d apply(const Eigen::Vector3d& p_world) const { return R * p_world + t; }
  Rect apply(const Rect& r_world) const {
    return Rect{apply(r_world.corner), R * r_world.u, R * r_world.v};
  }
};

inline Pose look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  const Eigen::Vector3d z = (target - eye).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Pose pose;
  pose.R.row(0) = x.transpose();
  pose.R.row(1) = y.transpose();
  pose.R.row(2) = z.transpose();
  pose.t = -pose.R * eye;
  return pose;
}

// A box standing on a table, seen from the front and above. World frame: z up, the
// table is the square [-table/2, table/2]^2 at z = 0, the box [-box/2, box/2]^2 x [0, box]
// (five faces, the bottom lies on the table). The camera is about 0.9 m away, 40 deg
// above the table. Rects 0 is the table, 1..5 the box faces.
struct BoxOnTable {
  std::vector<Rect> rects;  // in the camera frame
  static constexpr int kTable = 0;
};

inline BoxOnTable box_on_table(double box_m = 0.10, double table_m = 0.50) {
  const double h = box_m / 2;
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
  std::vector<Rect> world = {
      centered_rect({0, 0, 0}, X, table_m, Y, table_m),      // table
      centered_rect({0, 0, box_m}, X, box_m, Y, box_m),      // box top
      centered_rect({0, -h, h}, X, box_m, Z, box_m),         // box front (-y)
      centered_rect({0, h, h}, X, box_m, Z, box_m),          // box back (+y)
      centered_rect({-h, 0, h}, Y, box_m, Z, box_m),         // box left (-x)
      centered_rect({h, 0, h}, Y, box_m, Z, box_m),          // box right (+x)
  };
  const double dist = 0.9, elev = deg2rad(40.0), azim = deg2rad(-30.0);
  const Eigen::Vector3d target(0, 0, h);
  const Eigen::Vector3d eye = target + dist * Eigen::Vector3d(std::sin(azim) * std::cos(elev),
                                                              -std::cos(azim) * std::cos(elev), std::sin(elev));
  const Pose pose = look_at(eye, target);
  BoxOnTable scene;
  for (const Rect& r : world) scene.rects.push_back(pose.apply(r));
  return scene;
}

// --- small helpers ----------------------------------------------------------------------

// The label most points of rect `which` carry, and the fraction of them carrying it.
inline std::pair<std::uint32_t, double> majority(const RenderedScene& sc, const std::vector<std::uint32_t>& labels, int which) {
  std::map<std::uint32_t, std::size_t> count;
  std::size_t total = 0;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (sc.rect_of_point[i] != which) continue;
    ++count[labels[i]];
    ++total;
  }
  if (total == 0) return {0, 0.0};
  auto best = std::max_element(count.begin(), count.end(), [](auto& a, auto& b) { return a.second < b.second; });
  return {best->first, double(best->second) / double(total)};
}

// An unorganized cloud of the given points.
inline PointCloud unorganized(std::vector<Eigen::Vector3f> points) {
  PointCloud cloud;
  cloud.width = static_cast<std::uint32_t>(points.size());
  cloud.height = 1;
  cloud.points = std::move(points);
  return cloud;
}

inline std::size_t finite_count(const PointCloud& cloud) {
  return static_cast<std::size_t>(
      std::count_if(cloud.points.begin(), cloud.points.end(), [](const Eigen::Vector3f& p) { return p.allFinite(); }));
}

// The same cloud with its points (and normals/colours) in a shuffled order, unorganized.
// perm[i] is the new index of old point i.
inline PointCloud shuffled(const PointCloud& cloud, std::uint32_t seed, std::vector<std::size_t>& perm) {
  std::vector<std::size_t> order(cloud.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::mt19937 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);  // order[new] = old
  perm.assign(cloud.size(), 0);
  PointCloud out;
  out.width = static_cast<std::uint32_t>(cloud.size());
  out.height = 1;
  for (std::size_t n = 0; n < order.size(); ++n) {
    perm[order[n]] = n;
    out.points.push_back(cloud.points[order[n]]);
    if (cloud.has_colors()) out.colors.push_back(cloud.colors[order[n]]);
    if (cloud.has_normals()) out.normals.push_back(cloud.normals[order[n]]);
  }
  return out;
}

}  // namespace lccp::test
