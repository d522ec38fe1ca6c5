// FilterConfig::boundary_points_by_plane: a voxel that straddles a seam holds
// points of both surfaces; with the key, a point that lies on the other
// surface goes to that surface's segment. Noise-free rendered scenes, P1; and
// two boxes face to face on a support plane, with and without Kinect noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "lccp/core/lccp.hpp"
#include "lccp/io/config_file.hpp"
#include "robot_scenes.hpp"
#include "test_clouds.hpp"

namespace lccp {
namespace {

// The distance from p to the rectangle r (not its plane: its nearest point).
double to_rect(const test::Rect& r, const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = p - r.corner;
  const double a = std::clamp(q.dot(r.u) / r.u.squaredNorm(), 0.0, 1.0);
  const double b = std::clamp(q.dot(r.v) / r.v.squaredNorm(), 0.0, 1.0);
  return (p - (r.corner + a * r.u + b * r.v)).norm();
}

// Points not in their rect's segment, farther than `beyond_m` from every rect of another segment.
std::size_t strays(const test::RenderedScene& scene, const std::vector<test::Rect>& rects, bool by_plane,
                   double beyond_m) {
  LccpConfig config;
  config.filter.boundary_points_by_plane = by_plane;
  const SegmentationResult r = LccpSegmenter(config).segment(scene.cloud);
  std::vector<std::uint32_t> major(rects.size());
  for (std::size_t k = 0; k < rects.size(); ++k) major[k] = test::majority(scene, r.labels, static_cast<int>(k)).first;
  std::size_t count = 0;
  for (std::size_t i = 0; i < r.labels.size(); ++i) {
    if (scene.rect_of_point[i] < 0) continue;
    const auto k = static_cast<std::size_t>(scene.rect_of_point[i]);
    if (r.labels[i] == major[k]) continue;
    double seam = 1e9;
    for (std::size_t j = 0; j < rects.size(); ++j) {
      if (major[j] != major[k]) seam = std::min(seam, to_rect(rects[j], scene.cloud.points[i].cast<double>()));
    }
    count += seam > beyond_m ? 1 : 0;
  }
  return count;
}

// A box on a table (test_clouds.hpp): the table's points in the voxels of the
// box's foot lie on the table's plane; the paper's labelling gives them the box.
TEST(BoundaryPointsByPlane, ABoxsFootKeepsNoTablePoint) {
  const test::BoxOnTable box = test::box_on_table();
  const test::RenderedScene scene = test::render(box.rects);
  EXPECT_GT(strays(scene, box.rects, false, 0.002), 10u);
  EXPECT_EQ(strays(scene, box.rects, true, 0.002), 0u);
}

// A wall on a floor, 1.3 m away, the seam moved off the camera cells' faces
// so that its voxels hold points of both planes (a few mm of each).
TEST(BoundaryPointsByPlane, AConcaveSeamsVoxelsGiveEachPointToItsPlane) {
  test::ConcaveCorner corner = test::concave_corner(1.3, 0.10, 0.20);
  const Eigen::Vector3d shift(0, 0.0013, 0.0011);
  corner.wall.corner += shift, corner.table.corner += shift;
  const test::RenderedScene scene = test::render({corner.wall, corner.table});
  EXPECT_GT(strays(scene, {corner.wall, corner.table}, false, 0.002), 50u);
  EXPECT_EQ(strays(scene, {corner.wall, corner.table}, true, 0.002), 0u);
}

// On in P1, P2 and the robot preset; off in the paper's method (config.hpp).
TEST(BoundaryPointsByPlane, OnByDefaultOffInThePapersMethod) {
  const std::filesystem::path dir(LCCP_CONFIG_DIR);
  EXPECT_TRUE(LccpConfig{}.filter.boundary_points_by_plane);
  EXPECT_TRUE(load_config(dir / "p1.yaml").objects.filter.boundary_points_by_plane);
  EXPECT_TRUE(load_config(dir / "p2.yaml").objects.filter.boundary_points_by_plane);
  EXPECT_TRUE(load_config(dir / "robot.yaml").objects.filter.boundary_points_by_plane);
  EXPECT_FALSE(load_config(dir / "paper.yaml").objects.filter.boundary_points_by_plane);
}

// The points that change segment with the key, and the least distance of one
// of them from its own patch's plane over the centring tolerance of one sample
// there (half a depth step plus three times the support plane's noise).
struct Moved {
  std::size_t count = 0;
  double least_over_tolerance = 1e9;
};

Moved moved_points(const test::ContactView& view) {
  LccpConfig config = load_config(std::filesystem::path(LCCP_CONFIG_DIR) / "robot.yaml").objects;
  const test::ContactScene scene = test::contact_scene(test::two_boxes_touching(), view);
  config.filter.boundary_points_by_plane = false;
  const SegmentationResult kept = LccpSegmenter(config).segment(scene.cloud);
  config.filter.boundary_points_by_plane = true;
  const SegmentationWork w = LccpSegmenter(config).run(scene.cloud);
  EXPECT_TRUE(w.support.has_value());
  Moved m;
  for (std::size_t i = 0; i < kept.labels.size(); ++i) {
    if (w.result.labels[i] == kept.labels[i] || kept.labels[i] == 0) continue;
    const Eigen::Vector3f& p = scene.cloud.points[i];
    const std::uint32_t s = w.supervoxels.supervoxel_of_voxel[w.grid.voxel_of_point[i]];
    const double own = std::abs(w.supervoxels.normals[s].dot(p - w.supervoxels.centroids[s]));
    const double tolerance = 0.5 * config.sensor.step_per_m2() * p.z() * p.z() + 3.0 * w.support->noise_m;
    m.count += 1, m.least_over_tolerance = std::min(m.least_over_tolerance, own / tolerance);
  }
  return m;
}

// With a support plane, a point moves only if it lies off its own patch's
// plane by more than one sample's noise: noise-free, the points of one box in
// the other's voxels move; with the Kinect's noise, no point within its noise
// of its own patch does.
TEST(BoundaryPointsByPlane, WithASupportPlaneAPointWithinItsNoiseStays) {
  for (const bool noisy : {false, true}) {
    test::ContactView view;
    view.elevation_deg = 30, view.noisy = noisy;
    const Moved m = moved_points(view);
    if (!noisy) {
      EXPECT_GE(m.count, 10u);
    }
    if (m.count > 0) {
      EXPECT_GT(m.least_over_tolerance, 1.0) << (noisy ? "noisy" : "noise-free");
    }
    std::printf("[seam] %s: %zu points moved, the nearest to its own plane at %.2f tolerances\n",
                noisy ? "Kinect noise" : "noise-free", m.count, m.least_over_tolerance);
  }
}

}  // namespace
}  // namespace lccp
